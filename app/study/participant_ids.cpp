#include "app/study/participant_ids.h"

#include <cstring>
#include <stdexcept>

namespace cb {

const char kParticipantIdAlphabet[] = "23456789ABCDEFGHJKMNPQRSTUVWXYZ";

namespace {

// SplitMix64 (Steele, Lea, Flood: "Fast splittable pseudorandom number generators", 2014).
uint64_t splitMix64(uint64_t* state) {
  uint64_t z = (*state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

std::string ParticipantIdScheme::idFor(int number) const {
  if (number < 1) throw std::invalid_argument("participant numbers start at 1");
  if (kind == Kind::kCounter) {
    std::string digits_text = std::to_string(number);
    if (int(digits_text.size()) < digits)
      digits_text.insert(0, size_t(digits - int(digits_text.size())), '0');
    return prefix + digits_text;
  }
  const size_t alphabet_size = std::strlen(kParticipantIdAlphabet);
  uint64_t state = seed ^ (uint64_t(number) * 0xD1B54A32D192ED03ull);
  std::string id = prefix;
  for (int i = 0; i < length; ++i) id += kParticipantIdAlphabet[splitMix64(&state) % alphabet_size];
  return id;
}

}  // namespace cb
