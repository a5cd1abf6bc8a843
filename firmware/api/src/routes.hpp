#pragma once

#include <httplib.h>

#include "tilejet/api/api_backend.hpp"

namespace tilejet::api {

void add_job_routes(httplib::Server& server, ApiBackend& backend);
void add_line_routes(httplib::Server& server, ApiBackend& backend);

// Answers {"error": message, "field": field} with the ApiError's status.
void reply_error(httplib::Response& res, int status, const std::string& field,
                 const std::string& message);
void reply_json(httplib::Response& res, int status, const nlohmann::json& body);

}  // namespace tilejet::api
