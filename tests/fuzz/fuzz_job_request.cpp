// libFuzzer: the body of POST /api/jobs, as clients (the CLI, later the panel) send it.
#include <cstdint>
#include <string_view>

#include "tilejet/api/job_request.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        tilejet::api::parse_job_request(std::string_view(reinterpret_cast<const char*>(data), size),
                                        360);
    } catch (const tilejet::api::ApiError&) {
    }
    return 0;
}
