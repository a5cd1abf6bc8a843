#pragma once

#include <modbus/modbus.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "conveyor.hpp"
#include "tilejet/drivers/register_map.hpp"

// The PLC's Modbus TCP face: a real libmodbus server on loopback serving the register map, with
// the link faults the control socket injects (slow replies, a dropped link).
namespace tilejet::linesim {

class ModbusServer {
  public:
    // Called before each reply so input registers are fresh, and after each write with the
    // names of the holding registers that changed.
    struct Hooks {
        std::function<void()> refresh;
        std::function<void(const std::vector<std::string>&)> written;
    };

    ModbusServer(const std::string& host, int port, drivers::RegisterMap map, Hooks hooks);
    ~ModbusServer();

    int port() const { return port_; }
    std::uint32_t get(const std::string& name) const;
    void set(const std::string& name, std::uint32_t value);

    // For the event loop: the fds to poll, then one call with the readable ones.
    std::vector<int> fds() const;
    void on_readable(int fd, ns now);
    // Sends the delayed replies that are due; returns when the next one is.
    std::optional<ns> send_due(ns now);

    void set_delay(std::chrono::milliseconds delay) { delay_ = delay; }
    std::chrono::milliseconds delay() const { return delay_; }
    // Resets every connection (the client sees ECONNRESET mid-transfer) and refuses new ones
    // until `until`.
    void drop_link(ns until);
    bool link_down(ns now) const { return now < link_down_until_; }
    size_t clients() const { return clients_.size(); }

  private:
    struct Pending {
        ns due;
        int fd;
        std::vector<std::uint8_t> query;
    };

    void accept_client(ns now);
    void close_client(int fd, bool reset);
    void answer(int fd, const std::uint8_t* query, int length);
    // Exception 3 for writes above a register's max, before libmodbus stores them.
    bool reject_out_of_range(const std::uint8_t* query, int length);
    std::uint16_t* word(const drivers::Register& r);

    drivers::RegisterMap map_;
    Hooks hooks_;
    modbus_t* ctx_ = nullptr;
    modbus_mapping_t* mapping_ = nullptr;
    int listen_fd_ = -1;
    int port_ = 0;
    std::vector<int> clients_;
    std::deque<Pending> pending_;
    std::chrono::milliseconds delay_{0};
    ns link_down_until_{0};
    int header_length_ = 7;
};

}  // namespace tilejet::linesim
