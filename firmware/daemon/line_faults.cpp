#include "line_faults.hpp"

namespace tilejet::daemon {

nlohmann::json line_faults(const LineSnapshot& s) {
    nlohmann::json list = nlohmann::json::array();
    const auto add = [&](const char* code, std::string title, const char* action,
                         const char* severity) {
        list.push_back({{"code", code},
                        {"title", std::move(title)},
                        {"action", action},
                        {"severity", severity}});
    };
    if (s.estop_latched || s.status == LineStatus::estop)
        add("estop", "Emergency stop",
            "Find out why it was pressed and make the line safe. Release the e-stop button, "
            "then press Acknowledge. The tile that was under the heads is printed again.",
            "stop");
    if (!s.link_up)
        add("plc_link", "No connection to the PLC",
            "Check that the PLC is powered and its network cable is in. The controller "
            "reconnects by itself; the job goes on where it stopped.",
            "stop");
    if (s.plc_fault_code != 0)
        add("plc_fault", "PLC fault " + std::to_string(s.plc_fault_code),
            "Read the fault on the PLC's display and clear its cause there. The line restarts "
            "when the PLC reports ready.",
            "stop");
    else if (s.counter_fault)
        add("plc_counter", "PLC readings cannot be trusted: " + s.reason,
            "The conveyor is stopped and the heads hold their tiles. Check the PLC (did it "
            "restart? is its speed sensor sound?), then press Acknowledge: the controller asks the heads what they hold "
            "and goes on without printing a tile twice.",
            "stop");
    else if (s.status == LineStatus::faulted && s.link_up)
        add("faulted", "Line stopped: " + s.reason,
            "Clear the cause shown; the controller goes on by itself when it is gone. If it "
            "stays, call the line engineer.",
            "stop");
    if (s.reason.find("render behind") != std::string::npos)
        add("render_behind", "Tile rendering cannot keep up",
            "The conveyor runs slower until the controller has tiles ready. Nothing to do; if "
            "it lasts, tell the engineer (tile size and resolution set the pace).",
            "warning");
    return list;
}

}  // namespace tilejet::daemon
