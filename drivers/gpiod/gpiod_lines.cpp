#include "tilejet/drivers/gpiod/gpiod_lines.hpp"

#include <gpiod.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace tilejet::drivers::gpiod {

namespace {

constexpr const char* kConsumer = "tilejet";

std::string errno_text() {
    return std::strerror(errno);
}

}  // namespace

void GpiodLines::ChipCloser::operator()(gpiod_chip* chip) const {
    gpiod_chip_close(chip);  // also releases every line requested on it
}

GpiodLines::GpiodLines(const GpioConfig& config) : chip_name_(config.chip) {
    chip_.reset(gpiod_chip_open_lookup(config.chip.c_str()));
    if (!chip_)
        throw std::runtime_error("[gpio] chip: cannot open GPIO chip '" + config.chip +
                                 "': " + errno_text());
    auto find = [&](const std::string& key, const std::string& name) {
        gpiod_line* line = gpiod_chip_find_line(chip_.get(), name.c_str());
        if (!line)
            throw std::runtime_error("[gpio] " + key + ": chip '" + config.chip +
                                     "' has no line named '" + name + "'");
        return line;
    };
    for (GpioInput i : kGpioInputs) {
        const std::string key(config_key(i));
        gpiod_line* line = find(key, config.input_names[size_t(i)]);
        // Physical levels: LatchedGpio applies active_low, the same way for every backend.
        if (gpiod_line_request_both_edges_events(line, kConsumer) != 0)
            throw std::runtime_error("[gpio] " + key + ": cannot request edge events on line '" +
                                     config.input_names[size_t(i)] + "': " + errno_text());
        inputs_[size_t(i)] = line;
    }
    for (GpioOutput o : kGpioOutputs) {
        const std::string key(config_key(o));
        gpiod_line* line = find(key, config.output_names[size_t(o)]);
        if (gpiod_line_request_output(line, kConsumer, 0) != 0)
            throw std::runtime_error("[gpio] " + key + ": cannot request line '" +
                                     config.output_names[size_t(o)] +
                                     "' as output: " + errno_text());
        outputs_[size_t(o)] = line;
    }
}

GpiodLines::~GpiodLines() = default;

RawEdge GpiodLines::edge_from_event(GpioInput input, int event_type, const timespec& ts) {
    if (event_type != GPIOD_LINE_EVENT_RISING_EDGE && event_type != GPIOD_LINE_EVENT_FALLING_EDGE)
        throw std::runtime_error("gpiod: unknown event type " + std::to_string(event_type) +
                                 " on " + std::string(config_key(input)));
    return RawEdge{input, event_type == GPIOD_LINE_EVENT_RISING_EDGE,
                   std::chrono::seconds(ts.tv_sec) + std::chrono::nanoseconds(ts.tv_nsec)};
}

std::optional<RawEdge> GpiodLines::wait_edge(std::chrono::microseconds timeout) {
    gpiod_line_bulk bulk;
    gpiod_line_bulk_init(&bulk);
    for (gpiod_line* line : inputs_)
        gpiod_line_bulk_add(&bulk, line);
    gpiod_line_bulk events;
    gpiod_line_bulk_init(&events);
    const timespec ts{time_t(timeout.count() / 1000000), long(timeout.count() % 1000000) * 1000};
    const int rc = gpiod_line_event_wait_bulk(&bulk, &ts, &events);
    if (rc < 0)
        throw std::runtime_error("gpiod: waiting for edges on " + chip_name_ + ": " + errno_text());
    if (rc == 0) return std::nullopt;
    // One event per call; the rest stay queued in the kernel for the next call.
    gpiod_line* line = gpiod_line_bulk_get_line(&events, 0);
    gpiod_line_event event;
    if (gpiod_line_event_read(line, &event) != 0)
        throw std::runtime_error("gpiod: reading an edge on " + chip_name_ + ": " + errno_text());
    for (GpioInput i : kGpioInputs)
        if (inputs_[size_t(i)] == line) return edge_from_event(i, event.event_type, event.ts);
    throw std::runtime_error("gpiod: an edge on a line tilejet did not request");
}

bool GpiodLines::read(GpioInput input) {
    const int v = gpiod_line_get_value(inputs_[size_t(input)]);
    if (v < 0)
        throw std::runtime_error("gpiod: reading " + std::string(config_key(input)) + ": " +
                                 errno_text());
    return v == 1;
}

void GpiodLines::write(GpioOutput output, bool level) {
    std::lock_guard lock(write_mutex_);
    if (gpiod_line_set_value(outputs_[size_t(output)], level ? 1 : 0) != 0)
        throw std::runtime_error("gpiod: setting " + std::string(config_key(output)) + ": " +
                                 errno_text());
}

}  // namespace tilejet::drivers::gpiod
