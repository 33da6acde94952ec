// Deterministic stand-in for libFuzzer when building with gcc: feeds the target its seeds and then
// mutations of them (bit flips, byte edits, insertions of format tokens, deletions, splices,
// truncations) from a fixed-seed generator, for at most --max-runs inputs or --seconds seconds.
// usage: <driver> [--seconds S] [--max-runs N] [seed files...]
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
std::vector<std::string> fuzzSeeds();  // built-in seeds of each target
std::vector<std::string> fuzzTokens();  // format tokens worth inserting

namespace {
const std::string* g_current = nullptr;

// On a crash, save the input that caused it (reproduce: <driver> --max-runs 0 crash-input.bin).
extern "C" void onCrash(int sig) {
  if (g_current) {
    if (FILE* f = std::fopen("crash-input.bin", "wb")) {
      std::fwrite(g_current->data(), 1, g_current->size(), f);
      std::fclose(f);
    }
    std::fprintf(stderr, "crash (signal %d) on a %zu-byte input, saved to crash-input.bin\n", sig, g_current->size());
  }
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

std::string mutate(const std::string& in, const std::vector<std::string>& seeds, const std::vector<std::string>& tokens,
                   std::mt19937_64& rng) {
  std::string s = in;
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const std::size_t pos = s.empty() ? 0 : rng() % s.size();
    switch (rng() % 7) {
      case 0:
        if (!s.empty()) s[pos] = static_cast<char>(s[pos] ^ (1 << (rng() % 8)));
        break;
      case 1:
        if (!s.empty()) s[pos] = static_cast<char>(rng());
        break;
      case 2: s.insert(pos, tokens[rng() % tokens.size()]); break;
      case 3:
        if (!s.empty()) s.erase(pos, 1 + rng() % 16);
        break;
      case 4: {
        const std::string& o = seeds[rng() % seeds.size()];
        if (!o.empty()) s.insert(pos, o.substr(rng() % o.size(), 1 + rng() % 64));
        break;
      }
      case 5: s.resize(pos); break;
      default:
        if (!s.empty()) s.insert(pos, std::string(1 + rng() % 8, s[pos]));
        break;
    }
  }
  if (s.size() > 1 << 20) s.resize(1 << 20);
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  double seconds = 10;
  long max_runs = 200000;
  std::vector<std::string> seeds = fuzzSeeds();
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--seconds") && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--max-runs") && i + 1 < argc) {
      max_runs = std::atol(argv[++i]);
    } else {
      std::ifstream f(argv[i], std::ios::binary);
      std::stringstream ss;
      ss << f.rdbuf();
      if (f) seeds.push_back(ss.str());
    }
  }
  const std::vector<std::string> tokens = fuzzTokens();
  std::mt19937_64 rng(20261121);
  const auto t0 = std::chrono::steady_clock::now();
  long runs = 0;
  std::signal(SIGABRT, onCrash);
  std::signal(SIGSEGV, onCrash);
  for (const std::string& s : seeds) {
    g_current = &s;
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
    ++runs;
  }
  while (runs < max_runs &&
         std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds) {
    const std::string m = mutate(seeds[rng() % seeds.size()], seeds, tokens, rng);
    g_current = &m;
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(m.data()), m.size());
    ++runs;
  }
  std::printf("%ld inputs, no crash\n", runs);
  return 0;
}
