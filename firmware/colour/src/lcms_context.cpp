#include "lcms_context.hpp"

namespace tilejet::colour::detail {

LcmsContext::LcmsContext() : context_(cmsCreateContext(nullptr, this)) {
    cmsSetLogErrorHandlerTHR(context_, &LcmsContext::on_error);
}

LcmsContext::~LcmsContext() {
    cmsDeleteContext(context_);
}

std::string LcmsContext::take_error() {
    std::string e;
    e.swap(last_error_);
    return e;
}

void LcmsContext::on_error(cmsContext context, cmsUInt32Number, const char* text) {
    auto* self = static_cast<LcmsContext*>(cmsGetContextUserData(context));
    if (self && text) self->last_error_ = text;
}

}  // namespace tilejet::colour::detail
