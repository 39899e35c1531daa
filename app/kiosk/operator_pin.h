// The operator panel's PIN, kept out of every config file: <data dir>/operator-pin holds a
// crypt(3) hash (yescrypt, libcrypt's strongest default, salted) and nothing else (not the PIN's
// length: entry ends with Enter, so a guesser learns nothing from the file; files written before,
// "<digits> <hash>", are read and their length ignored), mode
// 0600 and owned by the service's user (under the unit, /var/lib/cloudbrush is 0750
// cloudbrush:cloudbrush: only root and the service read it). There is no default PIN: until one
// is set (at the kiosk the first time the operator combination is typed, or beforehand with
// `cloudbrush kiosk --set-pin`) the panel asks for a new one.
// Wrong PINs lock the panel with growing delays — the third wrong one in a row 60 s, every
// further one twice as long as the last, up to an hour — and the count and the end of the lock
// are kept in <data dir>/operator-lockout (wall-clock time), so a restart does not reset them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

namespace cb {

// A salted crypt(3) hash of `pin` ("" when libcrypt fails).
std::string hashOperatorPin(const std::string& pin);
// Whether `pin` matches `hash` (constant time in crypt's own comparison of equal-length strings).
bool operatorPinMatches(const std::string& pin, const std::string& hash);
// "" when `pin` is 4 to 12 digits; else why not.
std::string operatorPinProblem(const std::string& pin);

class OperatorPinGuard {
 public:
  static constexpr const char* kPinFile = "operator-pin";
  static constexpr const char* kLockoutFile = "operator-lockout";
  static constexpr int kFreeTries = 2;         // wrong PINs in a row before the first lock
  static constexpr double kFirstLockS = 60.0;  // then doubling per further wrong PIN
  static constexpr double kLongestLockS = 3600.0;

  // `wall_s`: Unix seconds (defaults to the system clock; tests inject theirs). Reads the PIN and
  // lockout files (a bad one is reported through `problem()` and counts as no PIN / no lock).
  explicit OperatorPinGuard(std::string data_dir, std::function<double()> wall_s = nullptr);

  bool hasPin() const { return !hash_.empty(); }
  // Sets a new PIN (4..12 digits): hashed, written atomically with mode 0600; clears the lock.
  bool setPin(const std::string& pin, std::string* error);

  enum class Result { kRight, kWrong, kLockedNow, kStillLocked };
  // Checks a typed PIN; a wrong one is counted and persisted. kLockedNow: this one started a lock.
  Result check(const std::string& typed);
  double lockedForSeconds() const;  // > 0 while locked
  double lastLockSeconds() const { return last_lock_s_; }
  int failures() const { return failures_; }
  const std::string& problem() const { return problem_; }

 private:
  void load();
  void saveLockout();
  std::string data_dir_;
  std::function<double()> wall_s_;
  std::string hash_;
  int failures_ = 0;  // wrong in a row
  double locked_until_s_ = 0.0;
  double last_lock_s_ = 0.0;
  std::string problem_;
};

}  // namespace cb
