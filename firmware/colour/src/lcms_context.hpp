#pragma once

// RAII over LittleCMS handles, and a context whose error handler keeps the last message so that
// a failure can be reported with the file it concerns (LittleCMS only logs).

#include <lcms2.h>

#include <memory>
#include <string>

namespace tilejet::colour::detail {

class LcmsContext {
  public:
    LcmsContext();
    ~LcmsContext();
    LcmsContext(const LcmsContext&) = delete;
    LcmsContext& operator=(const LcmsContext&) = delete;

    cmsContext get() const { return context_; }
    // The last error LittleCMS reported in this context ("" if none), and forget it.
    std::string take_error();

  private:
    static void on_error(cmsContext context, cmsUInt32Number code, const char* text);
    cmsContext context_;
    std::string last_error_;
};

struct ProfileCloser {
    void operator()(void* p) const { cmsCloseProfile(p); }
};
struct TransformDeleter {
    void operator()(void* t) const { cmsDeleteTransform(t); }
};
struct It8Deleter {
    void operator()(void* h) const { cmsIT8Free(h); }
};
struct ToneCurveDeleter {
    void operator()(cmsToneCurve* c) const { cmsFreeToneCurve(c); }
};
using Profile = std::unique_ptr<void, ProfileCloser>;
using Transform = std::unique_ptr<void, TransformDeleter>;
using It8 = std::unique_ptr<void, It8Deleter>;
using ToneCurve = std::unique_ptr<cmsToneCurve, ToneCurveDeleter>;

}  // namespace tilejet::colour::detail
