#include "modbus_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tilejet::linesim {

using drivers::Register;
using drivers::RegisterTable;

ModbusServer::ModbusServer(const std::string& host, int port, drivers::RegisterMap map, Hooks hooks)
    : map_(std::move(map)), hooks_(std::move(hooks)) {
    ctx_ = modbus_new_tcp(host.c_str(), port);
    if (!ctx_) throw std::runtime_error("modbus server: " + std::string(modbus_strerror(errno)));
    header_length_ = modbus_get_header_length(ctx_);
    // A client that stalls mid-request must not freeze the whole simulator.
    modbus_set_indication_timeout(ctx_, 0, 100000);
    modbus_set_byte_timeout(ctx_, 0, 100000);
    mapping_ = modbus_mapping_new_start_address(
        0, 0, 0, 0, map_.first_address(RegisterTable::holding), map_.span(RegisterTable::holding),
        map_.first_address(RegisterTable::input), map_.span(RegisterTable::input));
    if (!mapping_) throw std::runtime_error("modbus server: cannot allocate the register map");
    listen_fd_ = modbus_tcp_listen(ctx_, 16);
    if (listen_fd_ < 0)
        throw std::runtime_error("modbus server: cannot listen on " + host + ":" +
                                 std::to_string(port) + ": " + modbus_strerror(errno));
    fcntl(listen_fd_, F_SETFL, fcntl(listen_fd_, F_GETFL) | O_NONBLOCK);
    fcntl(listen_fd_, F_SETFD, FD_CLOEXEC);
    sockaddr_in bound{};
    socklen_t length = sizeof bound;
    getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&bound), &length);
    port_ = ntohs(bound.sin_port);  // the one the kernel chose when the config says 0
}

ModbusServer::~ModbusServer() {
    for (int fd : clients_)
        ::close(fd);
    if (listen_fd_ >= 0) ::close(listen_fd_);
    modbus_mapping_free(mapping_);
    modbus_free(ctx_);
}

std::uint16_t* ModbusServer::word(const Register& r) {
    return r.table == RegisterTable::input
               ? &mapping_->tab_input_registers[r.address - mapping_->start_input_registers]
               : &mapping_->tab_registers[r.address - mapping_->start_registers];
}

std::uint32_t ModbusServer::get(const std::string& name) const {
    const Register& r = map_.at(name);
    const std::uint16_t* w = const_cast<ModbusServer*>(this)->word(r);
    return r.words() == 2 ? (std::uint32_t(w[0]) << 16) | w[1] : w[0];
}

void ModbusServer::set(const std::string& name, std::uint32_t value) {
    const Register& r = map_.at(name);
    std::uint16_t* w = word(r);
    if (r.words() == 2) {
        w[0] = std::uint16_t(value >> 16);
        w[1] = std::uint16_t(value);
    } else {
        w[0] = std::uint16_t(value);
    }
}

std::vector<int> ModbusServer::fds() const {
    std::vector<int> fds = clients_;
    fds.push_back(listen_fd_);
    return fds;
}

void ModbusServer::accept_client(ns now) {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) return;
    if (link_down(now)) {
        // The link is "down": the connection is reset as soon as it is made.
        linger l{1, 0};
        setsockopt(fd, SOL_SOCKET, SO_LINGER, &l, sizeof l);
        ::close(fd);
        return;
    }
    clients_.push_back(fd);
}

void ModbusServer::close_client(int fd, bool reset) {
    if (reset) {
        linger l{1, 0};  // RST instead of FIN: the peer sees ECONNRESET, like a cut cable
        setsockopt(fd, SOL_SOCKET, SO_LINGER, &l, sizeof l);
    }
    ::close(fd);
    std::erase(clients_, fd);
    std::erase_if(pending_, [fd](const Pending& p) { return p.fd == fd; });
}

void ModbusServer::drop_link(ns until) {
    link_down_until_ = until;
    while (!clients_.empty())
        close_client(clients_.front(), true);
}

void ModbusServer::on_readable(int fd, ns now) {
    if (fd == listen_fd_) return accept_client(now);
    std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
    modbus_set_socket(ctx_, fd);
    const int length = modbus_receive(ctx_, query);
    if (length < 0) return close_client(fd, false);  // closed by the client, or garbage
    if (length == 0) return;
    if (delay_.count() > 0)
        pending_.push_back({now + delay_, fd, std::vector<std::uint8_t>(query, query + length)});
    else
        answer(fd, query, length);
}

std::optional<ns> ModbusServer::send_due(ns now) {
    while (!pending_.empty() && pending_.front().due <= now) {
        Pending p = std::move(pending_.front());
        pending_.pop_front();
        answer(p.fd, p.query.data(), int(p.query.size()));
    }
    if (pending_.empty()) return std::nullopt;
    return pending_.front().due;
}

bool ModbusServer::reject_out_of_range(const std::uint8_t* q, int length) {
    const int h = header_length_;
    if (length < h + 5) return false;
    const int function = q[h];
    const int address = (q[h + 1] << 8) | q[h + 2];
    std::vector<std::pair<int, std::uint16_t>> writes;
    if (function == MODBUS_FC_WRITE_SINGLE_REGISTER) {
        writes.emplace_back(address, std::uint16_t((q[h + 3] << 8) | q[h + 4]));
    } else if (function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS && length >= h + 6) {
        const int count = (q[h + 3] << 8) | q[h + 4];
        for (int i = 0; i < count && h + 6 + 2 * i + 1 < length; ++i)
            writes.emplace_back(address + i,
                                std::uint16_t((q[h + 6 + 2 * i] << 8) | q[h + 7 + 2 * i]));
    }
    for (const auto& [addr, value] : writes)
        for (const Register& r : map_.registers())
            if (r.table == RegisterTable::holding && r.words() == 1 && r.address == addr &&
                value > r.max) {
                modbus_reply_exception(ctx_, q, MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
                return true;
            }
    return false;
}

void ModbusServer::answer(int fd, const std::uint8_t* query, int length) {
    modbus_set_socket(ctx_, fd);
    if (reject_out_of_range(query, length)) return;
    hooks_.refresh();
    std::vector<std::uint16_t> before(mapping_->tab_registers,
                                      mapping_->tab_registers + mapping_->nb_registers);
    if (modbus_reply(ctx_, query, length, mapping_) < 0) return close_client(fd, false);
    std::vector<std::string> changed;
    for (const Register& r : map_.registers()) {
        if (r.table != RegisterTable::holding) continue;
        const size_t i = size_t(r.address - mapping_->start_registers);
        if (before[i] != mapping_->tab_registers[i] ||
            (r.words() == 2 && before[i + 1] != mapping_->tab_registers[i + 1]))
            changed.push_back(r.name);
    }
    // A write of the same value still counts as a command (writing run_command = 1 again after
    // a fault is how the controller restarts the line).
    const int function = query[header_length_];
    if (changed.empty() && (function == MODBUS_FC_WRITE_SINGLE_REGISTER ||
                            function == MODBUS_FC_WRITE_MULTIPLE_REGISTERS)) {
        const int address = (query[header_length_ + 1] << 8) | query[header_length_ + 2];
        for (const Register& r : map_.registers())
            if (r.table == RegisterTable::holding && r.address == address)
                changed.push_back(r.name);
    }
    if (!changed.empty()) hooks_.written(changed);
}

}  // namespace tilejet::linesim
