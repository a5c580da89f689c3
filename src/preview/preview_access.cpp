#include "preview/preview_access.hpp"

#include <cctype>
#include <random>

namespace penink {

std::string random_token() {
    std::random_device device;
    static const char* hex = "0123456789abcdef";
    std::string token;
    for (int i = 0; i < 4; ++i) {
        const std::uint32_t bits = device();
        for (int k = 0; k < 8; ++k) token += hex[(bits >> (4 * k)) & 15u];
    }
    return token;
}

bool host_allowed(const std::string& host, int port) {
    std::string lower;
    for (char c : host) lower += char(std::tolower(static_cast<unsigned char>(c)));
    std::string p = ":";
    p += std::to_string(port);
    return lower == "127.0.0.1" + p || lower == "localhost" + p;
}

bool token_matches(const std::string& given, const std::string& token) {
    if (token.empty() || given.size() != token.size()) return false;
    unsigned diff = 0;
    for (std::size_t i = 0; i < token.size(); ++i) diff |= unsigned(given[i] ^ token[i]);
    return diff == 0;
}

}  // namespace penink
