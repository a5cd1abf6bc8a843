#pragma once

#include <httplib.h>

#include "tilejet/api/api_backend.hpp"

namespace tilejet::api {

class EventHub;
class Gate;

void add_job_routes(httplib::Server& server, ApiBackend& backend);
void add_line_routes(httplib::Server& server, ApiBackend& backend);
void add_session_routes(httplib::Server& server, Gate& gate);
void add_event_routes(httplib::Server& server, EventHub& hub, Gate& gate);
void add_panel_routes(httplib::Server& server);
void add_picture_routes(httplib::Server& server, ApiBackend& backend);
void add_design_routes(httplib::Server& server, ApiBackend& backend);

// Answers {"error": message, "field": field} with the ApiError's status.
void reply_error(httplib::Response& res, int status, const std::string& field,
                 const std::string& message);
void reply_json(httplib::Response& res, int status, const nlohmann::json& body);

}  // namespace tilejet::api
