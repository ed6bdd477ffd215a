#include "schema/base64.h"

#include <stochtex/error.h>

#include <array>

namespace stochtex {

namespace {

constexpr char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// Character → 6-bit value, −1 for characters outside the alphabet.
const std::array<int, 256>& decoding_table()
{
    static const std::array<int, 256> table = [] {
        std::array<int, 256> t{};
        t.fill(-1);
        for (int i = 0; i < 64; ++i) t[static_cast<unsigned char>(alphabet[i])] = i;
        return t;
    }();
    return table;
}

}  // namespace

std::string base64_encode(const std::vector<std::uint8_t>& bytes)
{
    std::string text;
    text.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t group = std::uint32_t(bytes[i]) << 16;
        if (n > 1) group |= std::uint32_t(bytes[i + 1]) << 8;
        if (n > 2) group |= bytes[i + 2];
        for (std::size_t k = 0; k < 4; ++k) text += k <= n ? alphabet[(group >> (18 - 6 * k)) & 63] : '=';
    }
    return text;
}

std::vector<std::uint8_t> base64_decode(const std::string& text)
{
    if (text.size() % 4 != 0)
        throw Error("base64 text length " + std::to_string(text.size()) + " is not a multiple of 4");
    const std::array<int, 256>& table = decoding_table();
    std::vector<std::uint8_t> bytes;
    bytes.reserve(text.size() / 4 * 3);
    for (std::size_t i = 0; i < text.size(); i += 4) {
        const bool last = i + 4 == text.size();
        std::uint32_t group = 0;
        int padding = 0;
        for (std::size_t k = 0; k < 4; ++k) {
            const char c = text[i + k];
            // Padding: one or two '=' at the very end only.
            if (c == '=' && last && k >= 2 && (k == 3 || text[i + 3] == '=')) {
                ++padding;
                group <<= 6;
                continue;
            }
            const int value = table[static_cast<unsigned char>(c)];
            if (value < 0 || padding > 0)
                throw Error("invalid base64 character at offset " + std::to_string(i + k));
            group = group << 6 | std::uint32_t(value);
        }
        bytes.push_back(std::uint8_t(group >> 16));
        if (padding < 2) bytes.push_back(std::uint8_t(group >> 8));
        if (padding < 1) bytes.push_back(std::uint8_t(group));
    }
    return bytes;
}

}  // namespace stochtex
