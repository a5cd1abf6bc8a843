// /api/session: sign in (POST), who am I (GET), sign out (DELETE).
#include "gate.hpp"
#include "routes.hpp"
#include "tilejet/api/job_request.hpp"

namespace tilejet::api {

namespace {

nlohmann::json session_json(const Session& s) {
    return {{"user", s.user}, {"role", std::string(to_string(s.role))}, {"csrf", s.csrf}};
}

// HttpOnly: page scripts (and so injected ones) never see the id. SameSite=Strict: no other
// site's page makes the browser send it. No Secure flag: the API speaks plain HTTP on the
// line's own network or loopback.
std::string cookie_header(const std::string& value, std::chrono::seconds max_age) {
    return std::string(kSessionCookie) + "=" + value + "; Path=/; HttpOnly; SameSite=Strict; " +
           "Max-Age=" + std::to_string(max_age.count());
}

}  // namespace

void add_session_routes(Router& router, Gate& gate) {
    router
        .post("/api/session",
              [&gate](const HttpRequest& req, HttpResponse& res) {
                  const Session s = gate.sign_in(req);
                  res.set_header("Set-Cookie", cookie_header(s.id, gate.session_lifetime()));
                  reply_json(res, 200, session_json(s));
              })
        .lane = Lane::sign_in;
    router.get("/api/session", [&gate](const HttpRequest& req, HttpResponse& res) {
        const auto s = gate.session(req);
        if (!s) throw ApiError(401, "session", "sign in first");
        reply_json(res, 200, session_json(*s));
    });
    router.del("/api/session", [&gate](const HttpRequest& req, HttpResponse& res) {
        gate.sign_out(req);
        res.set_header("Set-Cookie", cookie_header("", std::chrono::seconds(0)));
        reply_json(res, 200, {{"signed_out", true}});
    });
}

}  // namespace tilejet::api
