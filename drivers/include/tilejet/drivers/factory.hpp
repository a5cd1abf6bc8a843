#pragma once

#include <memory>

#include "tilejet/drivers/config.hpp"
#include "tilejet/drivers/gpio.hpp"
#include "tilejet/drivers/head_sink.hpp"
#include "tilejet/drivers/line_control.hpp"

// The only place that knows which implementation backs each interface; the config decides
// ([line] control and heads, [gpio] backend). The daemon calls these and never names a backend.
namespace tilejet::drivers {

// One per thread that talks to the PLC (see ModbusLineControl).
std::unique_ptr<LineControl> make_line_control(const DriversConfig& config);
std::unique_ptr<Gpio> make_gpio(const DriversConfig& config);
std::unique_ptr<HeadSink> make_head_sink(const DriversConfig& config);

}  // namespace tilejet::drivers
