#pragma once

// The JSON API and the operator panel over HTTP. Routes live with their handlers
// (job_handlers.cpp, line_handlers.cpp, session_handlers.cpp, panel_handlers.cpp, ...); who may
// call which is one table in gate.cpp.
#include <memory>
#include <string>

#include "tilejet/api/access.hpp"
#include "tilejet/api/api_backend.hpp"

namespace tilejet::api {

class EventHub;
class Gate;
class HttpServer;
class Router;

class ApiServer {
  public:
    // Binds at once (port 0: the kernel picks); throws naming the address when it cannot, or
    // naming the user whose password hash is malformed. Users and limits from backend.access().
    ApiServer(ApiBackend& backend, const std::string& host, int port)
        : ApiServer(backend, host, port, backend.access()) {}
    ApiServer(ApiBackend& backend, const std::string& host, int port, const AccessSettings& access);
    // Ends the event streams first, so that open panels never hold up a shutdown.
    ~ApiServer();
    ApiServer(const ApiServer&) = delete;
    ApiServer& operator=(const ApiServer&) = delete;
    int port() const;

  private:
    std::unique_ptr<Gate> gate_;
    std::unique_ptr<EventHub> events_;
    std::unique_ptr<Router> router_;
    std::unique_ptr<HttpServer> server_;  // last: stopped first
};

}  // namespace tilejet::api
