#pragma once

// The JSON API over HTTP, on loopback only. Routes live with their handlers (job_handlers.cpp,
// line_handlers.cpp) so that the panel and sign-in can be added beside them.
#include <memory>
#include <string>
#include <thread>

#include "tilejet/api/api_backend.hpp"

namespace httplib {
class Server;
}

namespace tilejet::api {

class ApiServer {
  public:
    // Binds at once (port 0: the kernel picks); throws naming the address when it cannot.
    ApiServer(ApiBackend& backend, const std::string& host, int port);
    ~ApiServer();
    ApiServer(const ApiServer&) = delete;
    ApiServer& operator=(const ApiServer&) = delete;
    int port() const { return port_; }

  private:
    std::unique_ptr<httplib::Server> server_;
    int port_ = 0;
    std::thread thread_;
};

}  // namespace tilejet::api
