#pragma once
/** @file The fuzz bytes read as a sequence of choices, for targets that build structured values from them (libFuzzer's
 *  FuzzedDataProvider is clang's; the replays build with gcc too). Each choice takes the bytes it needs from the
 *  front; when the bytes run out every choice is its smallest, so any input is a complete program. */

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace inkgraph::fuzz {

class FuzzBytes {
public:
    FuzzBytes(const std::uint8_t* data, std::size_t size) : mData(data), mSize(size) {}

    std::size_t remaining() const { return mSize - mAt; }

    /** An integer in [low, high], from as many bytes as the range needs. */
    std::uint64_t integer(std::uint64_t low, std::uint64_t high) {
        const std::uint64_t span = high - low;
        std::uint64_t raw = 0;
        for (std::uint64_t left = span; left > 0 && mAt < mSize; left >>= 8) raw = (raw << 8) | mData[mAt++];
        return span == ~std::uint64_t(0) ? raw : low + raw % (span + 1);
    }
    int below(int count) { return int(integer(0, std::uint64_t(count - 1))); }
    bool boolean() { return integer(0, 1) == 1; }
    std::int64_t signed64() { return std::int64_t(integer(0, ~std::uint64_t(0))); }

    /** Eight bytes as a double, bit for bit: NaNs, infinities and subnormals included. */
    double real() {
        const std::uint64_t bits = integer(0, ~std::uint64_t(0));
        double result = 0;
        std::memcpy(&result, &bits, sizeof result);
        return result;
    }

    /** Up to `maxLength` bytes, the length chosen first. */
    std::string bytes(std::size_t maxLength) {
        const std::size_t length = std::size_t(integer(0, maxLength));
        const std::size_t taken = length < remaining() ? length : remaining();
        std::string result(reinterpret_cast<const char*>(mData + mAt), taken);
        mAt += taken;
        return result;
    }

    template <typename T, std::size_t N>
    const T& pick(const T (&items)[N]) {
        return items[integer(0, N - 1)];
    }

private:
    const std::uint8_t* mData;
    std::size_t mSize;
    std::size_t mAt = 0;
};

} // namespace inkgraph::fuzz
