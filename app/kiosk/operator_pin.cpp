#include "app/kiosk/operator_pin.h"

#include <crypt.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "app/core/atomic_file.h"

namespace cb {
namespace {

std::string slurp(const std::string& path, bool* exists) {
  std::ifstream in(path);
  *exists = bool(in);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

std::string hashOperatorPin(const std::string& pin) {
  char salt[CRYPT_GENSALT_OUTPUT_SIZE];
  if (!crypt_gensalt_rn(nullptr, 0, nullptr, 0, salt, sizeof salt)) return "";
  crypt_data data{};
  const char* hash = crypt_r(pin.c_str(), salt, &data);
  if (!hash || hash[0] == '*') return "";
  return hash;
}

bool operatorPinMatches(const std::string& pin, const std::string& hash) {
  if (hash.empty()) return false;
  crypt_data data{};
  const char* again = crypt_r(pin.c_str(), hash.c_str(), &data);
  return again && again[0] != '*' && std::strlen(again) == hash.size() &&
         std::equal(hash.begin(), hash.end(), again);
}

std::string operatorPinProblem(const std::string& pin) {
  if (pin.size() < 4 || pin.size() > 12) return "the PIN must have 4 to 12 digits";
  for (char c : pin)
    if (c < '0' || c > '9') return "the PIN must be digits only (typed on the number row)";
  return "";
}

OperatorPinGuard::OperatorPinGuard(std::string data_dir, std::function<double()> wall_s)
    : data_dir_(std::move(data_dir)), wall_s_(std::move(wall_s)) {
  if (!wall_s_)
    wall_s_ = [] {
      return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch())
          .count();
    };
  load();
}

void OperatorPinGuard::load() {
  bool exists = false;
  // operator-pin: "<hash>\n"; written before: "<digits> <hash>\n" (the length is ignored).
  std::istringstream pin(slurp(data_dir_ + "/" + kPinFile, &exists));
  std::string first, second;
  pin >> first >> second;
  hash_ = !first.empty() && first[0] == '$' && second.empty() ? first
          : !second.empty() && second[0] == '$' && !first.empty() &&
                  first.find_first_not_of("0123456789") == std::string::npos
              ? second
              : "";
  if (exists && hash_.empty())
    problem_ = data_dir_ + "/" + kPinFile + ": not a PIN record (set the PIN again)";
  // operator-lockout: "<failures in a row> <locked until, Unix s> <last lock, s>\n".
  std::istringstream lock(slurp(data_dir_ + "/" + kLockoutFile, &exists));
  if (exists && !(lock >> failures_ >> locked_until_s_ >> last_lock_s_)) {
    // Unreadable: the safe reading is a lock as long as the longest.
    failures_ = kFreeTries + 1;
    last_lock_s_ = kLongestLockS;
    locked_until_s_ = wall_s_() + kLongestLockS;
    problem_ = data_dir_ + "/" + kLockoutFile + ": unreadable; the panel stays locked for an hour";
  }
}

bool OperatorPinGuard::setPin(const std::string& pin, std::string* error) {
  if (const std::string problem = operatorPinProblem(pin); !problem.empty()) {
    *error = problem;
    return false;
  }
  const std::string hash = hashOperatorPin(pin);
  if (hash.empty()) {
    *error = "libcrypt could not hash the PIN";
    return false;
  }
  const mode_t old = ::umask(077);  // the temporary and so the file: 0600
  const bool ok = writeFileAtomically(data_dir_ + "/" + kPinFile, hash + "\n", error);
  ::umask(old);
  if (!ok) return false;
  hash_ = hash;
  failures_ = 0;
  locked_until_s_ = 0.0;
  last_lock_s_ = 0.0;
  saveLockout();
  return true;
}

double OperatorPinGuard::lockedForSeconds() const {
  return std::max(0.0, locked_until_s_ - wall_s_());
}

OperatorPinGuard::Result OperatorPinGuard::check(const std::string& typed) {
  if (lockedForSeconds() > 0.0) return Result::kStillLocked;
  if (operatorPinMatches(typed, hash_)) {
    failures_ = 0;
    last_lock_s_ = 0.0;
    saveLockout();
    return Result::kRight;
  }
  ++failures_;
  Result result = Result::kWrong;
  if (failures_ > kFreeTries) {
    last_lock_s_ = last_lock_s_ <= 0.0 ? kFirstLockS : std::min(kLongestLockS, 2.0 * last_lock_s_);
    locked_until_s_ = wall_s_() + last_lock_s_;
    result = Result::kLockedNow;
  }
  saveLockout();
  return result;
}

void OperatorPinGuard::saveLockout() {
  char text[96];
  std::snprintf(text, sizeof text, "%d %.3f %.3f\n", failures_, locked_until_s_, last_lock_s_);
  std::string error;
  if (!writeFileAtomically(data_dir_ + "/" + kLockoutFile, text, &error))
    std::fprintf(stderr, "cloudbrush kiosk: operator lockout NOT SAVED: %s\n", error.c_str());
}

}  // namespace cb
