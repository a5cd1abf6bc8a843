// Sign-in under pressure: parallel guesses, a viewer's session flood, and a page of another
// site (DNS rebinding) signing in with the controller's demo accounts.
#include <algorithm>
#include <barrier>
#include <map>

#include "harness.hpp"

namespace tilejet::attack {

namespace {

void parallel_sign_in(Target& t, const Scale& s, Verdict& v) {
    // All guesses in flight at once: a limit checked before the slow hash and counted after it
    // lets as many through as there are threads.
    std::vector<int> statuses(std::size_t(s.guesses), -1);
    std::vector<std::string> errors(std::size_t(s.guesses));
    std::barrier start(s.guesses);
    std::vector<std::thread> guessers;
    for (int i = 0; i < s.guesses; ++i)
        guessers.emplace_back([&, i] {
            start.arrive_and_wait();
            const Answer a = t.sign_in("olga", "wrong-guess-" + std::to_string(i));
            statuses[std::size_t(i)] = a.status;
            errors[std::size_t(i)] = a.error;
        });
    for (std::thread& g : guessers)
        g.join();
    t.guessed_now();
    const auto count = [&](int status) {
        return int(std::count(statuses.begin(), statuses.end(), status));
    };
    const int limit = api::SignInLimits{}.failures_per_user;
    const int wrong = count(401), limited = count(429);
    v.note(std::to_string(wrong) + " x 401, " + std::to_string(limited) + " x 429 (limit " +
           std::to_string(limit) + ")");
    v.expect(wrong <= limit,
             std::to_string(wrong) + " guesses judged, limit " + std::to_string(limit));
    std::map<std::string, int> others;
    for (std::size_t i = 0; i < statuses.size(); ++i)
        if (statuses[i] != 401 && statuses[i] != 429)
            ++others[statuses[i] < 0 ? "nothing (" + errors[i] + ")" : std::to_string(statuses[i])];
    for (const auto& [answer, n] : others)
        v.fail(std::to_string(n) + " guesses answered " + answer);
}

void session_flood(Target& t, const Scale& s, Verdict& v) {
    t.wait_sign_in_window();
    int refused = 0;
    for (int i = 0; i < s.viewer_sign_ins; ++i)
        refused += t.sign_in("vera", "vera-viewer-pw").status != 200;
    v.note(std::to_string(s.viewer_sign_ins - refused) + " viewer sessions opened");
    // A cap per user drops the viewer's own oldest sessions, never anybody else's.
    const int op = t.request(t.operator_session(), "GET", "/api/session").status;
    const int eng = t.request(t.engineer_session(), "GET", "/api/session").status;
    v.expect(op == 200, "operator's session answered " + std::to_string(op) + " afterwards");
    v.expect(eng == 200, "engineer's session answered " + std::to_string(eng) + " afterwards");
}

void foreign_host(Target& t, const Scale&, Verdict& v) {
    t.wait_sign_in_window();
    const std::string port = std::to_string(t.port());
    const std::vector<std::pair<const char*, httplib::Headers>> forged{
        {"Host and Origin",
         {{"Host", "evil.example:" + port}, {"Origin", "http://evil.example:" + port}}},
        {"Origin", {{"Origin", "http://evil.example:" + port}}},
        {"Host", {{"Host", "evil.example:" + port}}},
    };
    // The right password: only the names can make the daemon say no.
    for (const auto& [what, headers] : forged) {
        const int status = t.sign_in("vera", "vera-viewer-pw", headers).status;
        v.expect(status == 403, std::string("foreign ") + what + " answered " +
                                    std::to_string(status) + ", not 403");
    }
}

}  // namespace

std::vector<Attack> sign_in_attacks() {
    // The guessing goes last: it locks 127.0.0.1 out of signing in for a while.
    return {{"session-flood", session_flood},
            {"foreign-host-origin", foreign_host},
            {"parallel-sign-in", parallel_sign_in}};
}

}  // namespace tilejet::attack
