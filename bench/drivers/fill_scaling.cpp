// How fast this machine fills fresh memory, on one thread and on two: the part of a
// subdivision's time that no subdivision code can change.
//
//   fill_scaling [MB] [--rounds K]
//
// Fresh: a new anonymous mapping of MB megabytes (default 128) on a 2 MiB boundary with
// madvise(MADV_HUGEPAGE), as splinekit's CLI allocator maps its large blocks, each 4 KiB page
// written once: the kernel's page faults and page clearing, which every freshly allocated
// output pays. Warm: the same bytes written again (memset) into memory already mapped.
// T threads split the range into T contiguous parts. Median of K rounds (default 9).
// Prints one JSON object: {"mb": MB, "fresh_gbps": [t1, t2], "warm_gbps": [t1, t2]}.

#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

static double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// Runs body(begin, end) on `threads` threads over [0, n) in contiguous parts; seconds taken.
template <class F>
static double split(int threads, size_t n, F body) {
    std::vector<std::thread> pool;
    double t = now();
    for (int k = 0; k < threads; ++k) {
        size_t a = n * k / threads, b = n * (k + 1) / threads;
        pool.emplace_back([=] { body(a, b); });
    }
    for (auto& th : pool) th.join();
    return now() - t;
}

int main(int argc, char** argv) {
    size_t mb = 128;
    int rounds = 9;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--rounds") && i + 1 < argc) {
            rounds = atoi(argv[++i]);
        } else if (atoi(argv[i]) > 0) {
            mb = (size_t)atoi(argv[i]);
        } else {
            fprintf(stderr, "usage: fill_scaling [MB] [--rounds K]\n");
            return 2;
        }
    }
    const size_t huge = 2u << 20, n = mb << 20;
    double fresh[2], warm[2];
    for (int threads = 1; threads <= 2; ++threads) {
        std::vector<double> tf, tw;
        for (int r = 0; r < rounds; ++r) {
            void* raw = mmap(nullptr, n + huge, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            if (raw == MAP_FAILED) {
                perror("fill_scaling: mmap");
                return 1;
            }
            char* p = (char*)(((uintptr_t)raw + huge - 1) & ~(uintptr_t)(huge - 1));
            madvise(p, n, MADV_HUGEPAGE);
            tf.push_back(split(threads, n / 4096, [=](size_t a, size_t b) {
                for (size_t i = a; i < b; ++i) ((volatile char*)p)[i * 4096] = 1;
            }));
            tw.push_back(split(threads, n, [=](size_t a, size_t b) { memset(p + a, 2, b - a); }));
            munmap(raw, n + huge);
        }
        std::sort(tf.begin(), tf.end());
        std::sort(tw.begin(), tw.end());
        fresh[threads - 1] = n / tf[rounds / 2] / 1e9;
        warm[threads - 1] = n / tw[rounds / 2] / 1e9;
    }
    printf("{\"mb\": %zu, \"fresh_gbps\": [%.2f, %.2f], \"warm_gbps\": [%.2f, %.2f]}\n", mb, fresh[0], fresh[1], warm[0],
           warm[1]);
    return 0;
}
