#pragma once

// The JSON API and the operator panel over HTTP. Routes live with their handlers
// (job_handlers.cpp, line_handlers.cpp, session_handlers.cpp, panel_handlers.cpp, ...); who may
// call which is one table in gate.cpp.
#include <memory>
#include <string>
#include <thread>

#include "tilejet/api/access.hpp"
#include "tilejet/api/api_backend.hpp"

namespace httplib {
class Server;
}

namespace tilejet::api {

class EventHub;
class Gate;

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
    int port() const { return port_; }

  private:
    std::unique_ptr<Gate> gate_;
    std::unique_ptr<EventHub> events_;
    std::unique_ptr<httplib::Server> server_;
    int port_ = 0;
    std::thread thread_;
};

}  // namespace tilejet::api
