// Pseudonymous participant ids: never derived from names or anything a participant
// says. Schemes:
//   counter  PREFIX + the participant number, zero-padded to `digits` (P01, P02, ...)
//   random   PREFIX + `length` characters from an alphabet without look-alikes (no 0/O, 1/I/L),
//            drawn by SplitMix64 from (seed, participant number): reproducible by whoever holds
//            the seed, meaningless to anyone else
// The link from id to person, when a study needs one, lives only in the optional key file
// (CSV: participant,name,contact), which must be kept apart from the data.
#pragma once

#include <cstdint>
#include <string>

namespace cb {

struct ParticipantIdScheme {
  enum class Kind { kCounter, kRandom };
  Kind kind = Kind::kCounter;
  std::string prefix = "P";
  int digits = 2;        // counter
  uint64_t seed = 0;     // random
  int length = 6;        // random
  std::string key_file;  // absolute path, or empty: no key file

  // The id of participant `number` (>= 1).
  std::string idFor(int number) const;
};

// The characters random ids are drawn from.
extern const char kParticipantIdAlphabet[];

}  // namespace cb
