#pragma once

#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "conveyor.hpp"
#include "gpio_chip.hpp"
#include "modbus_server.hpp"
#include "peer.hpp"
#include "print_heads.hpp"
#include "tilejet/drivers/config.hpp"

// The line: PLC logic (ready, faults, e-stop, run/stop), conveyor, GPIO chip and heads, driven
// from one thread by one poll loop, so no state is ever shared between threads. Fault injection
// arrives on the control socket.
namespace tilejet::linesim {

class LineSimulator {
  public:
    LineSimulator(const drivers::DriversConfig& config, const std::string& print_log);
    ~LineSimulator();

    int modbus_port() const { return modbus_->port(); }
    // Runs until `stop` becomes true (checked at least every 50 ms).
    void run(const std::atomic<bool>& stop);

  private:
    void advance(ns now);
    void on_conveyor(const ConveyorEvent& e);
    void on_holding_written(const std::vector<std::string>& names);
    void refresh_inputs();
    void start_conveyor();
    void stop_conveyor();
    bool ready() const;
    void on_control(int fd, ns now);
    std::string control(const std::string& request, ns now);

    drivers::DriversConfig config_;
    Conveyor conveyor_;
    std::unique_ptr<ModbusServer> modbus_;
    std::unique_ptr<GpioChip> gpio_;
    std::unique_ptr<PrintHeads> heads_;
    int control_fd_ = -1;
    std::vector<Peer> control_peers_;
    bool estop_ = false;
    std::uint16_t fault_ = 0;
    bool running_ = false;
    std::uint32_t tile_counter_ = 0;
    // A speed sensor that lies: reported instead of the conveyor's speed ("speed-reading").
    std::optional<std::uint16_t> speed_reading_;
    bool counter_stuck_ = false;  // the PLC counts no tile ("counter-stuck on")
};

}  // namespace tilejet::linesim
