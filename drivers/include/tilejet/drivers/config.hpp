#pragma once

#include <array>
#include <chrono>
#include <string>

#include "tilejet/drivers/register_map.hpp"

// The config sections the drivers own. Each section maps to one struct and one parse function
// (config_parse.hpp); the daemon's config file adds sections other modules own ([colour], [api],
// [storage], ...) that load_drivers_config leaves alone.
namespace tilejet::drivers {

// [line]: what the conveyor looks like and which head sink to use.
struct LineConfig {
    double tile_length_mm = 300;     // along the direction of travel
    double tile_pitch_mm = 400;      // leading edge to leading edge
    double photo_eye_mm = 200;       // from the infeed, where tile 0's leading edge starts
    double heads_mm = 600;           // from the infeed, where the first head row fires
    std::string control = "modbus";  // LineControl backend (only "modbus": the sim is a server)
    std::string heads = "sim";       // HeadSink backend
    std::string register_map = "registers.toml";  // resolved against the config file's folder
};

// [modbus]: the link to the line PLC.
struct ModbusConfig {
    std::string transport = "tcp";  // "tcp" | "rtu"
    std::string host = "127.0.0.1";
    int port = 1502;
    std::string device = "/dev/ttyUSB0";  // rtu
    int baud = 19200;
    char parity = 'E';  // 'N', 'E' or 'O' (Modbus RTU's default is even parity)
    int data_bits = 8;
    int stop_bits = 1;
    int unit_id = 1;
    std::chrono::milliseconds response_timeout{200};
    std::chrono::milliseconds reconnect_min{50};
    std::chrono::milliseconds reconnect_max{500};
};

enum class GpioInput { photo_eye, estop, head_ready };
enum class GpioOutput { print_enable, beacon };
inline constexpr std::array kGpioInputs{GpioInput::photo_eye, GpioInput::estop,
                                        GpioInput::head_ready};
inline constexpr std::array kGpioOutputs{GpioOutput::print_enable, GpioOutput::beacon};

// [gpio]: which chip and lines; line names are what the board's device tree calls them.
struct GpioConfig {
    std::string backend = "sim";  // "sim" | "gpiod"
    std::string chip = "gpiochip0";
    std::array<std::string, 3> input_names{"PHOTO_EYE", "ESTOP", "HEAD_READY"};
    std::array<std::string, 2> output_names{"PRINT_ENABLE", "BEACON"};
    // Inputs wired active-low (an e-stop chain is normally closed: open circuit = stop).
    std::array<bool, 3> input_active_low{false, false, false};
    std::chrono::microseconds debounce{2000};
};

// [sim]: the line simulator's sockets and starting state. The simulator's Modbus server listens
// on [modbus] host:port, so one file configures both ends.
// Socket paths without a folder are in sim_runtime_directory().
struct SimConfig {
    std::string gpio_socket = "gpio.sock";
    std::string head_socket = "heads.sock";
    std::string control_socket = "control.sock";
    int speed_mm_s = 500;        // speed setpoint at power-up
    bool start_running = false;  // conveyor running at power-up
    int head_buffer_tiles = 2;   // separations the heads hold ahead of the tiles
    // false: the heads count the bytes but skip the SHA-256. At 289 MB a tile the hash costs a
    // core at about 5 tiles/s; a throughput benchmark on a small machine cannot spare it.
    bool head_checksums = true;
};

// Where the simulator's sockets live unless the config names a folder: whoever can write there
// can fake the e-stop line or the heads, so a private one. systemd's RuntimeDirectory=
// ($RUNTIME_DIRECTORY, e.g. /run/tilejet), else the user's ($XDG_RUNTIME_DIR/tilejet-sim), else
// /tmp/tilejet-sim-UID. The simulator makes it 0700 and refuses one that is not the user's own.
std::string sim_runtime_directory();

struct DriversConfig {
    std::string file;  // the config file, for messages
    LineConfig line;
    ModbusConfig modbus;
    GpioConfig gpio;
    SimConfig sim;
    RegisterMap registers;
};

// The sections load_drivers_config reads; the daemon's loader reports any section that no
// module's list claims.
inline constexpr std::array<const char*, 4> kDriverSections{"line", "modbus", "gpio", "sim"};

// Reads [line], [modbus], [gpio] and [sim] from the file (absent sections take their
// defaults), then the register map [line] names. Other sections are not looked at.
DriversConfig load_drivers_config(const std::string& path);

std::string_view to_string(GpioInput input);
std::string_view to_string(GpioOutput output);
// The config keys and sim protocol names: "photo_eye", "estop", "head_ready", ...
std::string_view config_key(GpioInput input);
std::string_view config_key(GpioOutput output);

}  // namespace tilejet::drivers
