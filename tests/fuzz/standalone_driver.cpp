// Runs a libFuzzer target without libFuzzer: every file of the corpus directories given on the
// command line, then deterministic mutations of them (bit flips, truncations, splices, random
// bytes). A crash or sanitizer report fails the test; a clean run prints how many inputs ran.
// The mutations' seed is CB_FUZZ_SEED when set (else 12345) and is always printed, so a failure
// reruns exactly. A target's LLVMFuzzerInitialize, when it has one, runs first, as libFuzzer does.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
extern "C" __attribute__((weak)) int LLVMFuzzerInitialize(int* argc, char*** argv);

int main(int argc, char** argv) {
  if (LLVMFuzzerInitialize) LLVMFuzzerInitialize(&argc, &argv);
  const char* seed_text = std::getenv("CB_FUZZ_SEED");
  const unsigned long long seed = seed_text ? std::strtoull(seed_text, nullptr, 10) : 12345;
  std::printf("fuzz driver: mutation seed %llu (CB_FUZZ_SEED)\n", seed);
  std::vector<std::vector<uint8_t>> corpus;
  for (int i = 1; i < argc; ++i) {
    std::filesystem::path p(argv[i]);
    std::vector<std::filesystem::path> files;
    if (std::filesystem::is_directory(p)) {
      for (auto& e : std::filesystem::directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path());
    } else if (std::filesystem::exists(p)) {
      files.push_back(p);
    } else {
      std::fprintf(stderr, "fuzz driver: corpus %s does not exist\n", argv[i]);
      return 2;
    }
    std::sort(files.begin(), files.end());
    for (auto& f : files) {
      std::ifstream in(f, std::ios::binary);
      corpus.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
  }
  corpus.push_back({});
  size_t runs = 0;
  for (auto& c : corpus) LLVMFuzzerTestOneInput(c.data(), c.size()), ++runs;
  std::mt19937_64 rng(seed);
  for (int round = 0; round < 20000; ++round) {
    std::vector<uint8_t> m = corpus[rng() % corpus.size()];
    switch (rng() % 5) {
      case 0:
        for (int k = 0; k < 4 && !m.empty(); ++k) m[rng() % m.size()] ^= uint8_t(1u << (rng() % 8));
        break;
      case 1:
        if (!m.empty()) m.resize(rng() % m.size());
        break;
      case 2: {
        auto& o = corpus[rng() % corpus.size()];
        if (!o.empty() && !m.empty()) {
          size_t at = rng() % m.size(), from = rng() % o.size();
          m.resize(at);
          m.insert(m.end(), o.begin() + long(from), o.end());
        }
        break;
      }
      case 3:
        for (int k = 0; k < 8 && !m.empty(); ++k) m[rng() % m.size()] = uint8_t(rng());
        break;
      default:
        m.resize(rng() % 512);
        for (auto& b : m) b = uint8_t(rng());
    }
    LLVMFuzzerTestOneInput(m.data(), m.size());
    ++runs;
  }
  std::printf("fuzz driver: %zu inputs ran without a crash\n", runs);
  return 0;
}
