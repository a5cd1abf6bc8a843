#pragma once

// Little-endian bytes of the map file (map_file.cpp) and of what its sections hold
// (cell_image_coding.cpp): a writer, and a bounds-checked reader whose every failure is a
// MapFileError naming the file, the section and what was being read.

#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "tilejet/synth/map_file.hpp"

namespace tilejet::synth::detail {

class Writer {
  public:
    std::vector<uint8_t> bytes;
    void u8s(const void* p, size_t n) {
        auto b = static_cast<const uint8_t*>(p);
        bytes.insert(bytes.end(), b, b + n);
    }
    template <typename T>
    void le(T v) {
        auto u = std::bit_cast<std::make_unsigned_t<T>>(v);
        for (size_t i = 0; i < sizeof(T); ++i)
            bytes.push_back(uint8_t(u >> (8 * i)));
    }
    void f32(float v) { le(std::bit_cast<uint32_t>(v)); }
    void f64(double v) { le(std::bit_cast<uint64_t>(v)); }
};

// Bounds-checked reads; every failure names the file, the section and what was being read.
class Reader {
  public:
    Reader(std::span<const uint8_t> data, std::string where)
        : data_(data), where_(std::move(where)) {}
    template <typename T>
    T le(const char* what) {
        need(sizeof(T), what);
        std::make_unsigned_t<T> u = 0;
        for (size_t i = 0; i < sizeof(T); ++i)
            u |= std::make_unsigned_t<T>(data_[pos_ + i]) << (8 * i);
        pos_ += sizeof(T);
        return std::bit_cast<T>(u);
    }
    float f32(const char* what) { return std::bit_cast<float>(le<uint32_t>(what)); }
    double f64(const char* what) { return std::bit_cast<double>(le<uint64_t>(what)); }
    std::span<const uint8_t> take(size_t n, const char* what) {
        need(n, what);
        auto s = data_.subspan(pos_, n);
        pos_ += n;
        return s;
    }
    size_t remaining() const { return data_.size() - pos_; }
    void done() const {
        if (pos_ != data_.size())
            throw MapFileError(where_ + ": " + std::to_string(data_.size() - pos_) +
                               " unexpected bytes at the end");
    }
    [[noreturn]] void fail(const std::string& why) const {
        throw MapFileError(where_ + ": " + why);
    }

  private:
    void need(size_t n, const char* what) const {
        if (data_.size() - pos_ < n) fail(std::string("ends before ") + what);
    }
    std::span<const uint8_t> data_;
    std::string where_;
    size_t pos_ = 0;
};

}  // namespace tilejet::synth::detail
