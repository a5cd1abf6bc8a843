#include "icc_profile.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>

#include "tilejet/colour/cmyk_transform.hpp"

namespace tilejet::colour::detail {

namespace {

constexpr size_t kIccHeaderBytes = 128;

uint32_t be32(const uint8_t* p) {
    return uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]);
}

const char* space_name(uint32_t s) {
    switch (s) {
        case cmsSigCmykData:
            return "CMYK";
        case cmsSigRgbData:
            return "RGB";
        case cmsSigGrayData:
            return "grey";
        case cmsSigLabData:
            return "Lab";
        case cmsSigXYZData:
            return "XYZ";
        default:
            return "an unsupported colour space";
    }
}

}  // namespace

uint32_t icc_data_space(const std::vector<uint8_t>& bytes) {
    return bytes.size() >= 20 ? be32(bytes.data() + 16) : 0;
}

IccProfile load_icc_profile(LcmsContext& lcms, const std::filesystem::path& path, const char* role,
                            cmsColorSpaceSignature space) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw ColourError("cannot read " + std::string(role) + " '" + path.string() +
                          "': " + std::strerror(errno));
    return parse_icc_profile(lcms,
                             {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()},
                             path, role, space);
}

IccProfile parse_icc_profile(LcmsContext& lcms, std::vector<uint8_t> bytes,
                             const std::filesystem::path& path, const char* role,
                             cmsColorSpaceSignature space) {
    const std::string where = std::string(role) + " '" + path.string() + "'";
    IccProfile p;
    p.bytes = std::move(bytes);
    if (p.bytes.size() < kIccHeaderBytes || std::memcmp(p.bytes.data() + 36, "acsp", 4) != 0)
        throw ColourError(where + " is not an ICC profile (no 'acsp' signature)");
    const uint32_t declared = be32(p.bytes.data());
    if (declared > p.bytes.size())
        throw ColourError(where + " is truncated: its header says " + std::to_string(declared) +
                          " bytes, the file has " + std::to_string(p.bytes.size()));
    const uint32_t actual = icc_data_space(p.bytes);
    if (actual != uint32_t(space))
        throw ColourError(where + " is " + space_name(actual) + "; the " + role + " must be " +
                          space_name(uint32_t(space)));
    p.handle.reset(cmsOpenProfileFromMemTHR(lcms.get(), p.bytes.data(), cmsUInt32Number(declared)));
    if (!p.handle) {
        const std::string why = lcms.take_error();
        throw ColourError(where + " cannot be read by LittleCMS" + (why.empty() ? "" : ": " + why));
    }
    return p;
}

}  // namespace tilejet::colour::detail
