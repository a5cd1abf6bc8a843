#include "router.hpp"

#include <algorithm>
#include <cctype>

namespace tilejet::api {

bool CaseInsensitiveLess::operator()(const std::string& a, const std::string& b) const {
    return std::lexicographical_compare(
        a.begin(), a.end(), b.begin(), b.end(),
        [](unsigned char x, unsigned char y) { return std::tolower(x) < std::tolower(y); });
}

std::string HttpRequest::get_header_value(const std::string& name) const {
    const auto it = headers.find(name);
    return it == headers.end() ? std::string() : it->second;
}

std::string HttpRequest::get_param_value(const std::string& name) const {
    const auto it = params.find(name);
    return it == params.end() ? std::string() : it->second;
}

Route& Router::add(const std::string& method, const std::string& pattern, Handler h) {
    routes_.push_back(Route{method, std::regex(pattern), std::move(h)});
    return routes_.back();
}

const Route* Router::find(HttpRequest& req) const {
    const std::string method = req.method == "HEAD" ? "GET" : req.method;
    for (const Route& r : routes_) {
        if (r.method != method) continue;
        std::smatch m;
        if (!std::regex_match(req.path, m, r.pattern)) continue;
        req.matches.assign(m.begin(), m.end());
        return &r;
    }
    return nullptr;
}

}  // namespace tilejet::api
