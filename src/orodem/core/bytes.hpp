// ByteWriter / ByteReader: a flat little-endian-as-stored byte buffer for
// checkpoints (io/checkpoint.cpp) and the Boundary save/load hooks. Values are
// stored as their raw bytes, so doubles come back bit for bit. The reader
// never reads past the end: a short buffer throws IoError("truncated ...").
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "orodem/core/error.hpp"

namespace orodem {

class ByteWriter {
public:
    template <class T>
    void put(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        buf_.append(reinterpret_cast<const char*>(&v), sizeof(T));
    }
    template <class T>
    void put_vector(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        put(static_cast<std::uint64_t>(v.size()));
        if (!v.empty()) buf_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
    }
    void put_string(std::string_view s) {
        put(static_cast<std::uint64_t>(s.size()));
        buf_.append(s.data(), s.size());
    }
    std::string& bytes() { return buf_; }
    const std::string& bytes() const { return buf_; }

private:
    std::string buf_;
};

class ByteReader {
public:
    explicit ByteReader(std::string_view b) : b_(b) {}
    template <class T>
    T get() {
        static_assert(std::is_trivially_copyable_v<T>);
        need(sizeof(T));
        T v;
        std::memcpy(&v, b_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    template <class T>
    void get(T& v) { v = get<T>(); }
    template <class T>
    void get_vector(std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto n = get<std::uint64_t>();
        if (n > (b_.size() - at_) / (sizeof(T) ? sizeof(T) : 1)) fail(n * sizeof(T));
        v.resize(static_cast<std::size_t>(n));
        if (n) std::memcpy(v.data(), b_.data() + at_, static_cast<std::size_t>(n) * sizeof(T));
        at_ += static_cast<std::size_t>(n) * sizeof(T);
    }
    std::string get_string() {
        const auto n = get<std::uint64_t>();
        if (n > b_.size() - at_) fail(n);
        std::string s(b_.substr(at_, static_cast<std::size_t>(n)));
        at_ += static_cast<std::size_t>(n);
        return s;
    }
    std::size_t remaining() const { return b_.size() - at_; }
    std::size_t offset() const { return at_; }

private:
    void need(std::size_t n) const {
        if (n > b_.size() - at_) fail(n);
    }
    [[noreturn]] void fail(std::uint64_t n) const {
        throw IoError("truncated data: needed " + std::to_string(n) + " more bytes at offset " +
                      std::to_string(at_) + " of " + std::to_string(b_.size()));
    }
    std::string_view b_;
    std::size_t at_ = 0;
};

}  // namespace orodem
