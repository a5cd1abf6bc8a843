#include "tilejet/drivers/factory.hpp"

#include "tilejet/drivers/gpiod/gpiod_lines.hpp"
#include "tilejet/drivers/latched_gpio.hpp"
#include "tilejet/drivers/modbus/modbus_line_control.hpp"
#include "tilejet/drivers/sim/sim_gpio_lines.hpp"
#include "tilejet/drivers/sim/sim_head_sink.hpp"

namespace tilejet::drivers {

std::unique_ptr<LineControl> make_line_control(const DriversConfig& config) {
    // [line] control has one value so far: the simulator is itself a Modbus server.
    return std::make_unique<ModbusLineControl>(config.modbus, config.registers);
}

std::unique_ptr<Gpio> make_gpio(const DriversConfig& config) {
    std::unique_ptr<GpioLines> lines;
    if (config.gpio.backend == "gpiod")
        lines = std::make_unique<gpiod::GpiodLines>(config.gpio);
    else
        lines = std::make_unique<sim::SimGpioLines>(config.sim.gpio_socket);
    return std::make_unique<LatchedGpio>(std::move(lines), config.gpio);
}

std::unique_ptr<HeadSink> make_head_sink(const DriversConfig& config) {
    return std::make_unique<sim::SimHeadSink>(config.sim.head_socket);
}

}  // namespace tilejet::drivers
