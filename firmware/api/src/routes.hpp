#pragma once

#include "router.hpp"
#include "tilejet/api/api_backend.hpp"

namespace tilejet::api {

class EventHub;
class Gate;

void add_job_routes(Router& router, ApiBackend& backend);
void add_line_routes(Router& router, ApiBackend& backend);
void add_session_routes(Router& router, Gate& gate);
void add_event_routes(Router& router, EventHub& hub, Gate& gate);
void add_panel_routes(Router& router);
void add_picture_routes(Router& router, ApiBackend& backend);
void add_design_routes(Router& router, ApiBackend& backend);

// Answers {"error": message, "field": field} with the ApiError's status.
void reply_error(HttpResponse& res, int status, const std::string& field,
                 const std::string& message);
void reply_json(HttpResponse& res, int status, const nlohmann::json& body);

}  // namespace tilejet::api
