#pragma once

// tilejetd's config: each module parses its own sections and the daemon composes them:
//   [line] [modbus] [gpio] [sim]  the line drivers (drivers/config_parse.hpp)
//   [colour]   ColourSettings for every job's CMYK transform (colour/colour_config.hpp)
//   [api]      the HTTP API's and panel's address, sessions, sign-in limits (api/api_config.hpp)
//   [[users]]  who may sign in, with which role and password hash (api/api_config.hpp)
// and the daemon's own:
//   [storage]  job store and previews (jobs/, tile_renderer)
//   [render]   render-ahead pool and the default resolution (render_ahead)
//   [print]    conveyor speeds and the print loop's timing (print_loop)
// An unknown section or key stops the daemon with file, section, key and line.
#include <chrono>
#include <string>

#include "tilejet/api/api_config.hpp"
#include "tilejet/colour/colour_settings.hpp"
#include "tilejet/drivers/config.hpp"

namespace tilejet::daemon {

struct StorageConfig {
    std::string database = "/var/lib/tilejet/jobs.db";
    std::string previews = "/var/lib/tilejet/previews";
    int preview_tiles = 8;  // sRGB proofs of each job's first tiles
    std::string designs;    // texture maps (*.tjmap) the panel offers; engineers upload here
    std::string profiles;   // CMYK output profiles (*.icc) the panel offers
};

struct RenderConfig {
    int threads = 0;      // render-ahead workers; 0 = all cores
    int queue_tiles = 8;  // rendered tiles kept ready ahead of the heads
    int dpi = 360;        // jobs that give no dpi
};

struct PrintConfig {
    int speed_mm_s = 500;               // conveyor speed while printing, when rendering keeps up
    int min_speed_mm_s = 100;           // slowest the daemon slows to before it stops the conveyor
    std::chrono::milliseconds poll{5};  // how often the PLC's tile counter is read
    std::chrono::milliseconds send_timeout{1000};  // one tile to the heads
    std::chrono::milliseconds send_margin{20};     // a send must end this long before a tile
    int head_buffer_tiles = 2;  // tiles the heads hold; from [sim] for the simulated heads
    std::chrono::seconds drain_timeout{30};  // SIGTERM: wait this long for the heads to empty
};

struct DaemonConfig {
    std::string file;
    drivers::DriversConfig drivers;
    colour::ColourSettings colour;
    StorageConfig storage;
    api::ApiConfig api;
    RenderConfig render;
    PrintConfig print;
};

// Reads and validates the whole file; relative paths resolve against the file's folder.
DaemonConfig load_daemon_config(const std::string& path);

}  // namespace tilejet::daemon
