#include "line_simulator.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "../unix_socket.hpp"

namespace tilejet::linesim {

using drivers::GpioInput;
using drivers::GpioOutput;

namespace {

ns monotonic_now() {
    return std::chrono::duration_cast<ns>(std::chrono::steady_clock::now().time_since_epoch());
}

std::string ok(nlohmann::ordered_json j = {}) {
    j["ok"] = true;
    return j.dump();
}

std::string error(const std::string& message) {
    return nlohmann::ordered_json{{"ok", false}, {"error", message}}.dump();
}

}  // namespace

LineSimulator::LineSimulator(const drivers::DriversConfig& config, const std::string& print_log)
    : config_(config), conveyor_(config.line) {
    modbus_ = std::make_unique<ModbusServer>(
        config.modbus.host, config.modbus.port, config.registers,
        ModbusServer::Hooks{[this] { refresh_inputs(); },
                            [this](const auto& names) { on_holding_written(names); }});
    gpio_ = std::make_unique<GpioChip>(config.sim.gpio_socket);
    heads_ = std::make_unique<PrintHeads>(config.sim.head_socket, config.sim.head_buffer_tiles,
                                          config.sim.head_checksums, print_log);
    control_fd_ = drivers::sim::listen_unix(config.sim.control_socket);
    modbus_->set("speed_setpoint", std::uint32_t(config.sim.speed_mm_s));
    conveyor_.advance(monotonic_now(), [](const ConveyorEvent&) {});
    if (config.sim.start_running) start_conveyor();
    refresh_inputs();
}

LineSimulator::~LineSimulator() {
    for (const Peer& p : control_peers_)
        ::close(p.fd);
    ::close(control_fd_);
    ::unlink(config_.sim.control_socket.c_str());
}

bool LineSimulator::ready() const {
    return !estop_ && fault_ == 0;
}

void LineSimulator::refresh_inputs() {
    modbus_->set("ready", ready());
    modbus_->set("running", running_);
    modbus_->set("fault_code", fault_);
    modbus_->set("speed_actual",
                 std::uint32_t(speed_reading_ ? *speed_reading_ : conveyor_.speed()));
    modbus_->set("tile_counter", tile_counter_);
    modbus_->set("estop", estop_);
}

void LineSimulator::start_conveyor() {
    advance(monotonic_now());
    running_ = true;
    modbus_->set("run_command", 1);
    conveyor_.set_speed(double(modbus_->get("speed_setpoint")));
}

void LineSimulator::stop_conveyor() {
    // The PLC drops its run command when it stops, so that nothing restarts the line except a
    // new run command.
    advance(monotonic_now());
    running_ = false;
    modbus_->set("run_command", 0);
    conveyor_.set_speed(0);
}

void LineSimulator::on_holding_written(const std::vector<std::string>& names) {
    for (const std::string& name : names) {
        if (name == "run_command") {
            if (modbus_->get("run_command") == 0)
                stop_conveyor();
            else if (ready())
                start_conveyor();
            else
                modbus_->set("run_command", 0);  // refused: not ready
        } else if (name == "speed_setpoint" && running_) {
            advance(monotonic_now());
            conveyor_.set_speed(double(modbus_->get("speed_setpoint")));
        }
    }
    refresh_inputs();
}

void LineSimulator::on_conveyor(const ConveyorEvent& e) {
    switch (e.kind) {
        case ConveyorEvent::eye_on:
            gpio_->set_input(GpioInput::photo_eye, true, e.time);
            break;
        case ConveyorEvent::eye_off:
            gpio_->set_input(GpioInput::photo_eye, false, e.time);
            break;
        case ConveyorEvent::at_heads:
            heads_->tile_arrives(e.tile, e.time, gpio_->output(GpioOutput::print_enable),
                                 gpio_->input(GpioInput::head_ready));
            if (!counter_stuck_) ++tile_counter_;
            break;
    }
}

void LineSimulator::advance(ns now) {
    conveyor_.advance(now, [this](const ConveyorEvent& e) { on_conveyor(e); });
}

std::string LineSimulator::control(const std::string& request, ns now) {
    std::istringstream in(request);
    std::string verb, arg, arg2;
    in >> verb >> arg >> arg2;
    try {
        if (verb == "estop" && (arg == "on" || arg == "off")) {
            estop_ = arg == "on";
            if (estop_) stop_conveyor();
            gpio_->set_input(GpioInput::estop, estop_, now);
        } else if (verb == "fault" && arg == "clear") {
            fault_ = 0;
        } else if (verb == "fault" && !arg.empty()) {
            const unsigned long code = std::stoul(arg);
            if (code == 0 || code > 0xffff) return error("fault code must be 1..65535");
            fault_ = std::uint16_t(code);
            stop_conveyor();
        } else if (verb == "drop-link" && !arg.empty()) {
            const double seconds = std::stod(arg);
            if (!(seconds >= 0 && seconds <= 3600)) return error("drop-link takes 0..3600 seconds");
            modbus_->drop_link(now + ns(std::int64_t(seconds * 1e9)));
        } else if (verb == "delay" && !arg.empty()) {
            const long ms = std::stol(arg);
            if (ms < 0 || ms > 60000) return error("delay takes 0..60000 ms");
            modbus_->set_delay(std::chrono::milliseconds(ms));
        } else if (verb == "glitch") {
            const long us = arg.empty() ? 300 : std::stol(arg);
            if (us <= 0 || us > 1000000) return error("glitch width takes 1..1000000 us");
            gpio_->glitch(GpioInput::photo_eye, now, std::chrono::microseconds(us));
        } else if (verb == "counter" && !arg.empty()) {
            // A PLC that restarted counts from 0 again; any other value is a counter that lies.
            const unsigned long value = std::stoul(arg);
            if (value > UINT32_MAX) return error("counter takes 0..4294967295");
            tile_counter_ = std::uint32_t(value);
        } else if (verb == "counter-stuck" && (arg == "on" || arg == "off")) {
            counter_stuck_ = arg == "on";
        } else if (verb == "speed-reading" && arg == "off") {
            speed_reading_.reset();
        } else if (verb == "speed-reading" && !arg.empty()) {
            // The speed register reads this whatever the conveyor does.
            const unsigned long value = std::stoul(arg);
            if (value > UINT16_MAX) return error("speed-reading takes 0..65535 or off");
            speed_reading_ = std::uint16_t(value);
        } else if (verb == "heads-reset") {
            heads_->reset_buffer();
        } else if (verb == "stop-conveyor") {
            stop_conveyor();
        } else if (verb == "start-conveyor") {
            if (!ready()) return error("the line is not ready (e-stop or fault)");
            start_conveyor();
        } else if (verb == "set" && !arg.empty() && !arg2.empty()) {
            const drivers::Register* r = config_.registers.find(arg);
            if (!r || !r->writable()) return error("no holding register named '" + arg + "'");
            const unsigned long value = std::stoul(arg2);
            if (value > r->max) return error(arg2 + " is above " + arg + "'s max");
            modbus_->set(arg, std::uint32_t(value));
            on_holding_written({arg});
        } else if (verb != "status") {
            return error("unknown request '" + request + "'");
        }
    } catch (const std::logic_error&) {  // stoul and friends on a non-number
        return error("bad number in '" + request + "'");
    }
    refresh_inputs();
    nlohmann::ordered_json j;
    j["estop"] = estop_;
    j["fault_code"] = fault_;
    j["ready"] = ready();
    j["running"] = running_;
    j["speed_setpoint"] = modbus_->get("speed_setpoint");
    j["speed_actual"] = conveyor_.speed();
    j["tile_counter"] = tile_counter_;
    j["photo_eye"] = gpio_->input(GpioInput::photo_eye);
    j["head_ready"] = gpio_->input(GpioInput::head_ready);
    j["print_enable"] = gpio_->output(GpioOutput::print_enable);
    j["beacon"] = gpio_->output(GpioOutput::beacon);
    j["delay_ms"] = modbus_->delay().count();
    j["link_down"] = modbus_->link_down(now);
    j["modbus_clients"] = modbus_->clients();
    j["gpio_clients"] = gpio_->clients();
    j["head_buffer"] = heads_->buffered();
    j["printed"] = heads_->printed();
    j["missed"] = heads_->missed();
    return ok(j);
}

void LineSimulator::on_control(int fd, ns now) {
    if (fd == control_fd_) {
        const int client = ::accept4(control_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (client >= 0) control_peers_.push_back(Peer{client, {}});
        return;
    }
    auto it = std::find_if(control_peers_.begin(), control_peers_.end(),
                           [fd](const Peer& p) { return p.fd == fd; });
    if (it == control_peers_.end()) return;
    const bool open = it->fill();
    std::string line;
    while (it->next_line(line))
        it->send(control(line, now) + "\n");
    if (!open || it->in.size() > 4096) {
        ::close(it->fd);
        control_peers_.erase(it);
    }
}

void LineSimulator::run(const std::atomic<bool>& stop) {
    enum Owner { modbus, gpio, heads, control };
    while (!stop) {
        ns now = monotonic_now();
        advance(now);
        ns wake = now + std::chrono::milliseconds(50);
        if (auto t = conveyor_.next_event(now)) wake = std::min(wake, *t);
        if (auto t = modbus_->send_due(now)) wake = std::min(wake, *t);

        std::vector<pollfd> fds;
        std::vector<Owner> owners;
        auto add = [&](const std::vector<int>& list, Owner owner) {
            for (int fd : list) {
                fds.push_back({fd, POLLIN, 0});
                owners.push_back(owner);
            }
        };
        add(modbus_->fds(), modbus);
        add(gpio_->fds(), gpio);
        add(heads_->fds(), heads);
        std::vector<int> control_fds{control_fd_};
        for (const Peer& p : control_peers_)
            control_fds.push_back(p.fd);
        add(control_fds, control);

        // Rounded up: waking a little late costs nothing (event times are exact), waking early
        // in a loop costs CPU.
        const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(
            wake - now + std::chrono::microseconds(999));
        if (::poll(fds.data(), fds.size(), int(std::max<long>(0, wait.count()))) <= 0) continue;
        now = monotonic_now();
        advance(now);  // tiles that reached the heads before anything just received
        for (size_t i = 0; i < fds.size(); ++i) {
            if (!(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
            switch (owners[i]) {
                case modbus:
                    modbus_->on_readable(fds[i].fd, now);
                    break;
                case gpio:
                    gpio_->on_readable(fds[i].fd);
                    break;
                case heads:
                    heads_->on_readable(fds[i].fd, now);
                    break;
                case control:
                    on_control(fds[i].fd, now);
                    break;
            }
        }
    }
}

}  // namespace tilejet::linesim
