#include "tilejet/colour/cmyk_tiff.hpp"

#include <tiffio.h>

#include <memory>

#include "tilejet/colour/cmyk_transform.hpp"

namespace tilejet::colour {

namespace {

struct TiffCloser {
    void operator()(TIFF* t) const { TIFFClose(t); }
};
using Tiff = std::unique_ptr<TIFF, TiffCloser>;

}  // namespace

void write_cmyk_tiff(const cv::Mat& cmyk, const std::vector<uint8_t>& icc,
                     const std::filesystem::path& path) {
    CV_Assert(cmyk.type() == CV_8UC4);
    const std::string name = path.string();
    Tiff tif(TIFFOpen(name.c_str(), "w"));
    if (!tif) throw ColourError("cannot write TIFF '" + name + "'");
    TIFFSetField(tif.get(), TIFFTAG_IMAGEWIDTH, uint32_t(cmyk.cols));
    TIFFSetField(tif.get(), TIFFTAG_IMAGELENGTH, uint32_t(cmyk.rows));
    TIFFSetField(tif.get(), TIFFTAG_SAMPLESPERPIXEL, 4);
    TIFFSetField(tif.get(), TIFFTAG_BITSPERSAMPLE, 8);
    TIFFSetField(tif.get(), TIFFTAG_PHOTOMETRIC, PHOTOMETRIC_SEPARATED);
    TIFFSetField(tif.get(), TIFFTAG_INKSET, INKSET_CMYK);
    TIFFSetField(tif.get(), TIFFTAG_PLANARCONFIG, PLANARCONFIG_CONTIG);
    TIFFSetField(tif.get(), TIFFTAG_COMPRESSION, COMPRESSION_LZW);
    TIFFSetField(tif.get(), TIFFTAG_ROWSPERSTRIP, TIFFDefaultStripSize(tif.get(), 0));
    if (!icc.empty()) TIFFSetField(tif.get(), TIFFTAG_ICCPROFILE, uint32_t(icc.size()), icc.data());
    for (int r = 0; r < cmyk.rows; ++r)
        if (TIFFWriteScanline(tif.get(), const_cast<uint8_t*>(cmyk.ptr(r)), uint32_t(r), 0) < 0)
            throw ColourError("cannot write TIFF '" + name + "' (row " + std::to_string(r) + ")");
}

CmykTiff read_cmyk_tiff(const std::filesystem::path& path) {
    const std::string name = path.string();
    Tiff tif(TIFFOpen(name.c_str(), "r"));
    if (!tif) throw ColourError("cannot read TIFF '" + name + "'");
    uint32_t w = 0, h = 0;
    uint16_t spp = 0, bps = 0, photometric = 0;
    TIFFGetField(tif.get(), TIFFTAG_IMAGEWIDTH, &w);
    TIFFGetField(tif.get(), TIFFTAG_IMAGELENGTH, &h);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_SAMPLESPERPIXEL, &spp);
    TIFFGetFieldDefaulted(tif.get(), TIFFTAG_BITSPERSAMPLE, &bps);
    TIFFGetField(tif.get(), TIFFTAG_PHOTOMETRIC, &photometric);
    if (spp != 4 || bps != 8 || photometric != PHOTOMETRIC_SEPARATED)
        throw ColourError("TIFF '" + name + "' is not 8-bit CMYK");
    CmykTiff out{cv::Mat(int(h), int(w), CV_8UC4), {}};
    for (uint32_t r = 0; r < h; ++r)
        if (TIFFReadScanline(tif.get(), out.cmyk.ptr(int(r)), r, 0) < 0)
            throw ColourError("TIFF '" + name + "' is damaged (row " + std::to_string(r) + ")");
    uint32_t icc_size = 0;
    void* icc = nullptr;
    if (TIFFGetField(tif.get(), TIFFTAG_ICCPROFILE, &icc_size, &icc) && icc)
        out.icc_profile.assign(static_cast<uint8_t*>(icc), static_cast<uint8_t*>(icc) + icc_size);
    return out;
}

}  // namespace tilejet::colour
