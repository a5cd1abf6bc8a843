#include "tilejet/drivers/modbus/modbus_line_control.hpp"

#include <modbus/modbus.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tilejet::drivers {

namespace {

bool is_exception_reply(int error) {
    return error > MODBUS_ENOBASE && error <= EMBXGTAR;
}

std::string describe(int error) {
    std::string text = modbus_strerror(error);
    if (is_exception_reply(error))
        return "the PLC answered exception " + std::to_string(error - MODBUS_ENOBASE) + " (" +
               text + ")";
    if (error == EMBBADDATA || error == EMBBADCRC || error == EMBBADEXC || error == EMBUNKEXC ||
        error == EMBBADSLAVE || error == EMBMDATA)
        return "malformed reply (" + text + ")";
    return text;
}

std::string block_label(const RegisterMap& map, RegisterTable table) {
    std::string names;
    for (const Register& r : map.registers())
        if (r.table == table) names += (names.empty() ? "" : ", ") + r.name;
    const int first = map.first_address(table);
    return std::string(to_string(table)) + " registers " + std::to_string(first) + ".." +
           std::to_string(first + map.span(table) - 1) + " (" + names + ")";
}

}  // namespace

void ModbusLineControl::ContextDeleter::operator()(modbus_t* ctx) const {
    modbus_close(ctx);
    modbus_free(ctx);
}

ModbusLineControl::ModbusLineControl(const ModbusConfig& config, RegisterMap registers)
    : config_(config),
      registers_(std::move(registers)),
      endpoint_(config.transport == "rtu"
                    ? "rtu " + config.device
                    : "tcp " + config.host + ":" + std::to_string(config.port)),
      owner_(std::this_thread::get_id()),
      backoff_(config.reconnect_min) {}

ModbusLineControl::~ModbusLineControl() = default;

void ModbusLineControl::check_thread() const {
    if (std::this_thread::get_id() != owner_)
        throw std::logic_error("modbus " + endpoint_ +
                               ": a ModbusLineControl is used only by the thread that made it "
                               "(libmodbus contexts are not thread-safe); make one per thread");
}

bool ModbusLineControl::connected() const {
    return ctx_ != nullptr;
}

ModbusLineControl::Context ModbusLineControl::open_context() const {
    Context ctx(config_.transport == "rtu"
                    ? modbus_new_rtu(config_.device.c_str(), config_.baud, config_.parity,
                                     config_.data_bits, config_.stop_bits)
                    : modbus_new_tcp(config_.host.c_str(), config_.port));
    if (!ctx)
        throw LinkError("modbus " + endpoint_ +
                        ": cannot create a context: " + modbus_strerror(errno));
    const auto timeout =
        std::chrono::duration_cast<std::chrono::microseconds>(config_.response_timeout);
    const auto sec = uint32_t(timeout.count() / 1000000),
               usec = uint32_t(timeout.count() % 1000000);
    modbus_set_response_timeout(ctx.get(), sec, usec);
    modbus_set_byte_timeout(ctx.get(), sec, usec);
    modbus_set_error_recovery(ctx.get(), MODBUS_ERROR_RECOVERY_NONE);
    if (modbus_set_slave(ctx.get(), config_.unit_id) == -1)
        throw LinkError("modbus " + endpoint_ + ": unit id " + std::to_string(config_.unit_id) +
                        ": " + modbus_strerror(errno));
    if (modbus_connect(ctx.get()) == -1)
        throw LinkError("modbus " + endpoint_ + ": cannot connect: " + modbus_strerror(errno));
    return ctx;
}

modbus_t* ModbusLineControl::context() {
    check_thread();
    if (ctx_) return ctx_.get();
    const auto now = Clock::now();
    if (now < next_attempt_) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(next_attempt_ - now).count();
        throw LinkError("modbus " + endpoint_ + ": link down, next reconnect attempt in " +
                        std::to_string(left) + " ms");
    }
    try {
        ctx_ = open_context();
        resync();
        backoff_ = config_.reconnect_min;
    } catch (const LinkError&) {
        ctx_.reset();
        next_attempt_ = Clock::now() + backoff_;
        backoff_ = std::min(backoff_ * 2, config_.reconnect_max);
        throw;
    }
    return ctx_.get();
}

void ModbusLineControl::fail(const std::string& what, int error) {
    const std::string message = "modbus " + endpoint_ + ": " + what + ": " + describe(error);
    if (is_exception_reply(error)) throw RegisterError(message);
    // Anything else leaves the link in an unknown state: drop it; the next call reconnects.
    ctx_.reset();
    next_attempt_ = Clock::now();
    throw LinkError(message);
}

std::vector<std::uint16_t> ModbusLineControl::read_block(RegisterTable table,
                                                         const std::string& what) {
    modbus_t* ctx = context();
    const int first = registers_.first_address(table), count = registers_.span(table);
    std::vector<std::uint16_t> words(size_t(count), 0);
    if (count == 0) return words;
    errno = 0;
    const int rc = table == RegisterTable::input
                       ? modbus_read_input_registers(ctx, first, count, words.data())
                       : modbus_read_registers(ctx, first, count, words.data());
    if (rc != count) fail("reading " + what, rc == -1 ? errno : EMBBADDATA);
    return words;
}

std::map<std::string, std::uint32_t> ModbusLineControl::decode(
    RegisterTable table, const std::vector<std::uint16_t>& words) const {
    std::map<std::string, std::uint32_t> values;
    const int first = registers_.first_address(table);
    for (const Register& r : registers_.registers()) {
        if (r.table != table) continue;
        const size_t i = size_t(r.address - first);
        values[r.name] = r.words() == 2 ? (std::uint32_t(words[i]) << 16) | words[i + 1] : words[i];
    }
    return values;
}

std::map<std::string, std::uint32_t> ModbusLineControl::read_all() {
    auto values =
        decode(RegisterTable::input,
               read_block(RegisterTable::input, block_label(registers_, RegisterTable::input)));
    values.merge(decode(
        RegisterTable::holding,
        read_block(RegisterTable::holding, block_label(registers_, RegisterTable::holding))));
    return values;
}

std::uint32_t ModbusLineControl::read(const std::string& name) {
    const Register& r = registers_.at(name);
    modbus_t* ctx = context();
    std::uint16_t words[2] = {0, 0};
    errno = 0;
    const int rc = r.table == RegisterTable::input
                       ? modbus_read_input_registers(ctx, r.address, r.words(), words)
                       : modbus_read_registers(ctx, r.address, r.words(), words);
    if (rc != r.words()) fail("reading " + r.label(), rc == -1 ? errno : EMBBADDATA);
    return r.words() == 2 ? (std::uint32_t(words[0]) << 16) | words[1] : words[0];
}

void ModbusLineControl::write_register(const Register& r, std::uint32_t value) {
    modbus_t* ctx = context();
    errno = 0;
    int rc;
    if (r.words() == 2) {
        const std::uint16_t words[2] = {std::uint16_t(value >> 16), std::uint16_t(value)};
        rc = modbus_write_registers(ctx, r.address, 2, words) == 2 ? 0 : -1;
    } else {
        rc = modbus_write_register(ctx, r.address, std::uint16_t(value)) == 1 ? 0 : -1;
    }
    if (rc != 0)
        fail("writing " + std::to_string(value) + " to " + r.label(), errno ? errno : EMBBADDATA);
}

void ModbusLineControl::write(const std::string& name, std::uint32_t value) {
    check_thread();
    const Register& r = registers_.at(name);
    if (!r.writable())
        throw RegisterError("modbus " + endpoint_ + ": " + r.label() +
                            " is read-only (input registers cannot be written)");
    if (value > r.max)
        throw RegisterError("modbus " + endpoint_ + ": " + std::to_string(value) +
                            " is out of range for " + r.label() + " (max " + std::to_string(r.max) +
                            (r.unit.empty() ? "" : " " + r.unit) + ")");
    // Remembered before sending: if the link is down, the re-sync writes it once it is back.
    if (r.retain) retained_[r.name] = value;
    write_register(r, value);
}

void ModbusLineControl::resync() {
    // Called right after a fresh connect: read everything, then put back what the controller
    // had set, in case the PLC restarted while the link was down.
    auto values = read_all();
    for (const auto& [name, value] : retained_)
        if (values[name] != value) write_register(registers_.at(name), value);
    ++resyncs_;
}

LineState ModbusLineControl::read_state() {
    const auto v = read_all();
    LineState s;
    s.ready = v.at("ready") != 0;
    s.running = v.at("running") != 0;
    s.estop = v.at("estop") != 0;
    s.fault_code = std::uint16_t(v.at("fault_code"));
    s.speed_mm_s = std::uint16_t(v.at("speed_actual"));
    s.speed_setpoint_mm_s = std::uint16_t(v.at("speed_setpoint"));
    s.run_commanded = v.at("run_command") != 0;
    s.tile_counter = v.at("tile_counter");
    return s;
}

void ModbusLineControl::set_speed(std::uint16_t mm_s) {
    write("speed_setpoint", mm_s);
}
void ModbusLineControl::run() {
    write("run_command", 1);
}
void ModbusLineControl::stop() {
    write("run_command", 0);
}

}  // namespace tilejet::drivers
