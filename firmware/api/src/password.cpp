#include "tilejet/api/password.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/rand.h>

#include <charconv>
#include <stdexcept>
#include <vector>

namespace tilejet::api {

namespace {

constexpr std::string_view kScheme = "pbkdf2-sha256";
constexpr int kSaltBytes = 16;
constexpr int kHashBytes = 32;

std::string base64(const std::vector<unsigned char>& bytes) {
    std::string out(4 * ((bytes.size() + 2) / 3), '\0');
    const int n = EVP_EncodeBlock(reinterpret_cast<unsigned char*>(out.data()), bytes.data(),
                                  int(bytes.size()));
    out.resize(size_t(n));
    return out;
}

std::vector<unsigned char> unbase64(std::string_view text) {
    if (text.empty() || text.size() % 4 != 0)
        throw std::invalid_argument("password hash: bad base64 length");
    std::vector<unsigned char> out(text.size() / 4 * 3);
    const int n = EVP_DecodeBlock(out.data(), reinterpret_cast<const unsigned char*>(text.data()),
                                  int(text.size()));
    if (n < 0) throw std::invalid_argument("password hash: bad base64");
    // EVP_DecodeBlock counts the '=' padding as zero bytes.
    size_t size = size_t(n);
    for (size_t i = text.size(); i > 0 && text[i - 1] == '='; --i)
        --size;
    out.resize(size);
    return out;
}

std::vector<unsigned char> derive(std::string_view password, const std::vector<unsigned char>& salt,
                                  int iterations, size_t bytes) {
    std::vector<unsigned char> key(bytes);
    if (PKCS5_PBKDF2_HMAC(password.data(), int(password.size()), salt.data(), int(salt.size()),
                          iterations, EVP_sha256(), int(key.size()), key.data()) != 1)
        throw std::runtime_error("PBKDF2 failed");
    return key;
}

struct ParsedHash {
    int iterations = 0;
    std::vector<unsigned char> salt, hash;
};

ParsedHash parse(std::string_view text) {
    std::vector<std::string_view> parts;
    size_t start = 0;
    while (true) {
        const size_t end = text.find('$', start);
        parts.push_back(text.substr(start, end - start));
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    if (parts.size() != 4 || parts[0] != kScheme)
        throw std::invalid_argument(
            "password hash: expected \"pbkdf2-sha256$ITERATIONS$SALT$HASH\" (tilejet passwd "
            "makes one)");
    ParsedHash p;
    const auto [end, ec] =
        std::from_chars(parts[1].data(), parts[1].data() + parts[1].size(), p.iterations);
    if (ec != std::errc() || end != parts[1].data() + parts[1].size() || p.iterations < 1)
        throw std::invalid_argument("password hash: bad iteration count");
    p.salt = unbase64(parts[2]);
    p.hash = unbase64(parts[3]);
    if (p.salt.size() < 4 || p.hash.size() < 16)
        throw std::invalid_argument("password hash: salt or hash too short");
    return p;
}

}  // namespace

std::string hash_password(std::string_view password, int iterations) {
    if (iterations < 1) throw std::invalid_argument("iterations must be at least 1");
    std::vector<unsigned char> salt(kSaltBytes);
    if (RAND_bytes(salt.data(), int(salt.size())) != 1)
        throw std::runtime_error("no random bytes for a salt");
    return std::string(kScheme) + "$" + std::to_string(iterations) + "$" + base64(salt) + "$" +
           base64(derive(password, salt, iterations, kHashBytes));
}

bool verify_password(std::string_view password, std::string_view hash) {
    const ParsedHash p = parse(hash);
    const auto key = derive(password, p.salt, p.iterations, p.hash.size());
    return CRYPTO_memcmp(key.data(), p.hash.data(), key.size()) == 0;
}

void check_password_hash(std::string_view hash) {
    parse(hash);
}

}  // namespace tilejet::api
