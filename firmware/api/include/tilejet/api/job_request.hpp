#pragma once

// Parsing and validating what clients send. Every rejection is an ApiError with the HTTP
// status and the field at fault, so a client (or the panel) can point at it.
#include <stdexcept>
#include <string>
#include <string_view>

#include "tilejet/jobs/job.hpp"

namespace tilejet::api {

class ApiError : public std::runtime_error {
  public:
    ApiError(int status, std::string field, const std::string& message)
        : std::runtime_error(message), status_(status), field_(std::move(field)) {}
    int status() const { return status_; }
    const std::string& field() const { return field_; }

  private:
    int status_;
    std::string field_;
};

// The largest request body the API reads (a job is a few hundred bytes).
inline constexpr std::size_t kMaxBodyBytes = 64 * 1024;

// POST /api/jobs: {"map": "/abs/path.tjmap", "seed": 7, "tiles": 50, "tile_mm": "300x300" or
// [300, 300], "dpi": 100, "profile": "/abs/line.icc", "layout": "scatter"|"wall",
// "wall_width": 4}. `default_dpi` fills a missing dpi; 0 leaves it 0, for the backend to take
// the design's. Throws ApiError (400) naming the field.
jobs::JobSpec parse_job_request(std::string_view body, int default_dpi);

// One tile's separations must fit the heads' protocol and memory (4 bytes a pixel, 1 GiB):
// throws ApiError (400, field dpi) when a tile of the spec's size and dpi does not.
void check_tile_fits(const jobs::JobSpec& spec);

// "300x300" -> {300, 300} in millimetres; throws ApiError naming `field`.
std::pair<double, double> parse_tile_mm(std::string_view text, const std::string& field);

}  // namespace tilejet::api
