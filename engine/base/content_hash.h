// A 64-bit hash of a byte stream, for telling whether a run's inputs changed (the checkpoint's
// fingerprint), not for security. The XXH64 round on four lanes of 8-byte words:
//   lane = rotl(lane + word * P2, 31) * P1,
// each lane a bijection of its state for a given word, so a changed word always changes its
// lane; the lanes, the byte count and a tail of under 32 bytes are mixed at the end. Four
// independent lanes keep the multiplier busy: about 0.2 cycles a byte, against 4 for a
// byte-at-a-time FNV-1a, so hashing a data file costs less than reading it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace vesselid {

class ContentHash {
 public:
  // Appends bytes; the digest does not depend on how the stream is cut into calls.
  void Add(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    total_ += size;
    if (pending_ > 0) {  // complete the stripe left from the last call
      const size_t take = std::min(size, kStripe - pending_);
      std::memcpy(stripe_ + pending_, bytes, take);
      pending_ += take;
      bytes += take;
      size -= take;
      if (pending_ < kStripe) return;
      Stripe(stripe_);
      pending_ = 0;
    }
    for (; size >= kStripe; bytes += kStripe, size -= kStripe) Stripe(bytes);
    std::memcpy(stripe_, bytes, size);
    pending_ = size;
  }
  void Add(const std::string& text) { Add(text.data(), text.size()); }

  std::uint64_t Digest() const {
    std::uint64_t h =
        Rotl(lane_[0], 1) + Rotl(lane_[1], 7) + Rotl(lane_[2], 12) + Rotl(lane_[3], 18);
    for (std::uint64_t lane : lane_) h = (h ^ Round(0, lane)) * kP1 + kP4;
    h += total_;
    for (size_t i = 0; i < pending_; ++i) h = Rotl(h ^ (stripe_[i] * kP5), 11) * kP1;
    h ^= h >> 33;
    h *= kP2;
    h ^= h >> 29;
    h *= kP3;
    return h ^ (h >> 32);
  }

 private:
  static constexpr size_t kStripe = 32;
  static constexpr std::uint64_t kP1 = 0x9E3779B185EBCA87ULL, kP2 = 0xC2B2AE3D27D4EB4FULL,
                                 kP3 = 0x165667B19E3779F9ULL, kP4 = 0x85EBCA77C2B2AE63ULL,
                                 kP5 = 0x27D4EB2F165667C5ULL;

  static std::uint64_t Rotl(std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
  static std::uint64_t Round(std::uint64_t lane, std::uint64_t word) {
    return Rotl(lane + word * kP2, 31) * kP1;
  }
  void Stripe(const unsigned char* p) {
    for (int i = 0; i < 4; ++i) {
      std::uint64_t word;
      std::memcpy(&word, p + 8 * i, 8);  // little-endian hosts; the digest is per machine
      lane_[i] = Round(lane_[i], word);
    }
  }

  std::uint64_t lane_[4] = {kP1 + kP2, kP2, 0, 0 - kP1};
  unsigned char stripe_[kStripe] = {};
  size_t pending_ = 0;
  std::uint64_t total_ = 0;
};

}  // namespace vesselid
