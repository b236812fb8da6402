// Verilator side of the canstar engine benchmark (see run.sh): replays a recorded
// stimulus (models/tests/common/stim.rs format) into one Verilated instance per
// stream, clocking each as canstar_hdl::drive::cycle does (inputs, rising edge,
// falling edge), checks the output hash against the compiled model's, then times
// the same replay without hashing. Rates are per second of this thread's CPU time.
//
// Built by run.sh with BENCH_TOP = the Verilated class and ports.h = the port adapters
// written by `cargo test -p canstar-models --test bench -- --ignored bench_print_verilator_files`.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <vector>

#include "verilated.h"
#include BENCH_TOP_HEADER

#include "ports.h"

static double cpu() {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + t.tv_nsec * 1e-9;
}

struct Stim {
    uint32_t streams = 0, inputs = 0;
    uint64_t cycles = 0;
    std::vector<uint8_t> data;
};

static Stim load(const char* path) {
    Stim s;
    FILE* f = fopen(path, "rb");
    if (!f) {
        perror(path);
        exit(2);
    }
    char magic[8];
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, "CSTIM1\0\0", 8) != 0 || fread(&s.streams, 4, 1, f) != 1 ||
        fread(&s.inputs, 4, 1, f) != 1 || fread(&s.cycles, 8, 1, f) != 1) {
        fprintf(stderr, "%s: not a stimulus file\n", path);
        exit(2);
    }
    uint8_t buf[1 << 16];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) s.data.insert(s.data.end(), buf, buf + n);
    fclose(f);
    return s;
}

// One pass over the stimulus; returns the output hash (FNV-1a, as OutHash in Rust) if `hash`.
static uint64_t replay(const Stim& s, std::vector<std::unique_ptr<BENCH_TOP>>& tops, bool hash) {
    uint64_t h = 0xcbf29ce484222325ULL;
    uint64_t out[N_OUT];
    size_t p = 0;
    for (uint64_t c = 0; c < s.cycles; c++) {
        for (uint32_t k = 0; k < s.streams; k++) {
            BENCH_TOP* t = tops[k].get();
            unsigned n = s.data[p++];
            for (unsigned j = 0; j < n; j++) {
                uint64_t v;
                memcpy(&v, &s.data[p + 1], 8);
                set_input(t, s.data[p], v);
                p += 9;
            }
            t->clock = 1;
            t->eval();
            t->clock = 0;
            t->eval();
            if (hash) {
                get_outputs(t, out);
                for (int i = 0; i < N_OUT; i++)
                    for (int b = 0; b < 8; b++) {
                        h ^= (out[i] >> (8 * b)) & 0xff;
                        h *= 0x100000001b3ULL;
                    }
            }
        }
    }
    return h;
}

static std::vector<std::unique_ptr<BENCH_TOP>> fresh(VerilatedContext* ctx, const Stim& s) {
    std::vector<std::unique_ptr<BENCH_TOP>> tops;
    for (uint32_t k = 0; k < s.streams; k++) {
        tops.emplace_back(new BENCH_TOP(ctx));
        tops.back()->clock = 0;
        tops.back()->eval();
    }
    return tops;
}

int main(int argc, char** argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: %s stim.bin expected-hash\n", argv[0]);
        return 2;
    }
    Stim s = load(argv[1]);
    uint64_t expect = strtoull(argv[2], nullptr, 16);
    auto ctx = std::make_unique<VerilatedContext>();
    auto tops = fresh(ctx.get(), s);
    uint64_t h = replay(s, tops, true);
    tops = fresh(ctx.get(), s);
    double t = cpu();
    replay(s, tops, false);
    double dt = cpu() - t;
    printf("%s: %u streams x %lu cycles, Verilator %.0f cycles/s per stream, output hash %016lx %s\n", argv[1], s.streams,
           (unsigned long)s.cycles, s.cycles * (double)s.streams / dt, (unsigned long)h,
           h == expect ? "(= compiled model)" : "(DIFFERS from the compiled model)");
    return h == expect ? 0 : 1;
}
