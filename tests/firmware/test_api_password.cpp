// Password hashes: PBKDF2-HMAC-SHA256 against a published test vector, salts, malformed hashes.
#include <catch2/catch.hpp>

#include "tilejet/api/password.hpp"

using namespace tilejet;

TEST_CASE("a password hash verifies the published PBKDF2-HMAC-SHA256 vector", "[api][password]") {
    // RFC 7914 section 11 lists PBKDF2-HMAC-SHA256("passwd", "salt", 1, 64); its first 32 bytes:
    // 55 ac 04 6e 56 e3 08 9f ec 16 91 c2 25 44 b6 05 f9 41 85 21 6d de 04 65 e6 8b 9d 57 c2 0d
    // ac bc. "c2FsdA==" is base64 of "salt"; the hash field is base64 of those 32 bytes.
    const std::string hash =
        "pbkdf2-sha256$1$c2FsdA==$VawEblbjCJ/sFpHCJUS2BflBhSFt3gRl5oudV8INrLw=";
    CHECK(api::verify_password("passwd", hash));
    CHECK_FALSE(api::verify_password("passwe", hash));
    CHECK_FALSE(api::verify_password("", hash));
}

TEST_CASE("each hash has its own salt and verifies only its password", "[api][password]") {
    const std::string a = api::hash_password("correct horse", 1000);
    const std::string b = api::hash_password("correct horse", 1000);
    CHECK(a != b);
    CHECK(a.starts_with("pbkdf2-sha256$1000$"));
    CHECK(api::verify_password("correct horse", a));
    CHECK(api::verify_password("correct horse", b));
    CHECK_FALSE(api::verify_password("correct horsE", a));
}

TEST_CASE("a malformed hash is an error, never a match", "[api][password]") {
    for (const char* bad : {"", "plain-text-password", "pbkdf2-sha256$x$c2FsdA==$AAAA",
                            "md5$1$c2FsdA==$VawEblbjCJ/sFpHCJUS2BflBhSFt3gRl5oudV8INrLw=",
                            "pbkdf2-sha256$1$c2FsdA==$!!!!"}) {
        INFO(bad);
        CHECK_THROWS_AS(api::verify_password("passwd", bad), std::invalid_argument);
    }
}
