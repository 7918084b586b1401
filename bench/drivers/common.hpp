// Shared helpers of the subdivision drivers: a small OBJ reader/writer (v and f lines only), the
// command line, a clock and the JSON line. File I/O is never inside the timed region.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

struct Tri {
    std::vector<double> xyz;  // 3 per vertex
    std::vector<int> tri;     // 3 per face (polygons: sizes[f] per face), 0-based
    std::vector<int> sizes;   // polygon meshes only: corners per face
    std::vector<double> nxyz; // optional: 3 per vertex, written as `vn` lines
    // sharpness tags (`t crease` / `t corner` lines): edge vertex pairs, vertices, sharpness
    std::vector<int> crease_pairs;
    std::vector<float> crease_sharpness;
    std::vector<int> corner_vertices;
    std::vector<float> corner_sharpness;
    int num_vertices() const { return int(xyz.size() / 3); }
    int num_faces() const { return sizes.empty() ? int(tri.size() / 3) : int(sizes.size()); }
};

// Reads `t crease N/M v0 .. vN-1 s ..` (the chain v0-v1, v1-v2, ...; one sharpness for all or
// one per edge) and `t corner N/M v.. s..` (0-based vertices), splinekit's and OpenSubdiv's OBJ
// tags. Other tags are skipped.
inline void read_tag(const char* path, long lineno, const char* line, Tri& m) {
    char name[64];
    int ni, nf, used;
    if (std::sscanf(line, "t %63s %d/%d%n", name, &ni, &nf, &used) != 3) return;
    std::string tag = name;
    if (tag != "crease" && tag != "corner") return;
    std::vector<long> ints;
    std::vector<float> floats;
    const char* s = line + used;
    for (int k = 0; k < ni + nf; ++k) {
        char* end;
        double x = std::strtod(s, &end);
        if (end == s) {
            std::fprintf(stderr, "%s:%ld: bad tag\n", path, lineno);
            std::exit(2);
        }
        if (k < ni) ints.push_back(long(x));
        else floats.push_back(float(x));
        s = end;
    }
    size_t items = tag == "crease" ? ints.size() - 1 : ints.size();
    if (ints.size() < (tag == "crease" ? 2u : 1u) || (floats.size() != 1 && floats.size() != items)) {
        std::fprintf(stderr, "%s:%ld: bad tag arguments\n", path, lineno);
        std::exit(2);
    }
    for (size_t k = 0; k < items; ++k) {
        float sharp = floats.size() == 1 ? floats[0] : floats[k];
        if (tag == "crease") {
            m.crease_pairs.push_back(int(ints[k]));
            m.crease_pairs.push_back(int(ints[k + 1]));
            m.crease_sharpness.push_back(sharp);
        } else {
            m.corner_vertices.push_back(int(ints[k]));
            m.corner_sharpness.push_back(sharp);
        }
    }
}

// Reads `v x y z` and `f a b c` (also a/b/c forms and negative indices) and the crease tags of
// read_tag; other lines are skipped. With `polygons`, faces of any size (recorded in `sizes`);
// otherwise triangles only.
inline Tri read_obj(const char* path, bool polygons = false) {
    FILE* f = std::fopen(path, "r");
    if (!f) {
        std::fprintf(stderr, "cannot open %s\n", path);
        std::exit(2);
    }
    Tri m;
    char line[4096];
    long lineno = 0;
    while (std::fgets(line, sizeof line, f)) {
        ++lineno;
        if (line[0] == 'v' && (line[1] == ' ' || line[1] == '\t')) {
            double x, y, z;
            if (std::sscanf(line + 2, "%lf %lf %lf", &x, &y, &z) != 3) {
                std::fprintf(stderr, "%s:%ld: bad vertex\n", path, lineno);
                std::exit(2);
            }
            m.xyz.insert(m.xyz.end(), {x, y, z});
        } else if (line[0] == 'f' && (line[1] == ' ' || line[1] == '\t')) {
            std::vector<int> face;
            char* s = line + 2;
            while (true) {
                while (*s == ' ' || *s == '\t') ++s;
                if (*s == '\0' || *s == '\n' || *s == '\r') break;
                char* end;
                long k = std::strtol(s, &end, 10);
                if (end == s) {
                    std::fprintf(stderr, "%s:%ld: bad face\n", path, lineno);
                    std::exit(2);
                }
                face.push_back(int(k > 0 ? k - 1 : m.num_vertices() + k));
                s = end;
                while (*s && *s != ' ' && *s != '\t' && *s != '\n' && *s != '\r') ++s;
            }
            if (polygons ? face.size() < 3 : face.size() != 3) {
                std::fprintf(stderr, "%s:%ld: %s\n", path, lineno, polygons ? "fewer than 3 corners" : "not a triangle");
                std::exit(2);
            }
            if (polygons) m.sizes.push_back(int(face.size()));
            m.tri.insert(m.tri.end(), face.begin(), face.end());
        } else if (line[0] == 't' && line[1] == ' ') {
            read_tag(path, lineno, line, m);
        }
    }
    std::fclose(f);
    return m;
}

// Writes positions with %.17g (exact round trip) and 1-based faces.
inline void write_obj(const char* path, const Tri& m, const std::string& comment) {
    FILE* f = std::fopen(path, "w");
    if (!f) {
        std::fprintf(stderr, "cannot write %s\n", path);
        std::exit(2);
    }
    std::fprintf(f, "# %s\n", comment.c_str());
    for (int v = 0; v < m.num_vertices(); ++v)
        std::fprintf(f, "v %.17g %.17g %.17g\n", m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]);
    for (size_t v = 0; 3 * v < m.nxyz.size(); ++v)
        std::fprintf(f, "vn %.17g %.17g %.17g\n", m.nxyz[3 * v], m.nxyz[3 * v + 1], m.nxyz[3 * v + 2]);
    if (m.sizes.empty()) {
        for (int t = 0; t < m.num_faces(); ++t)
            std::fprintf(f, "f %d %d %d\n", m.tri[3 * t] + 1, m.tri[3 * t + 1] + 1, m.tri[3 * t + 2] + 1);
    } else {
        size_t c = 0;
        for (int n : m.sizes) {
            std::fprintf(f, "f");
            for (int k = 0; k < n; ++k) std::fprintf(f, " %d", m.tri[c++] + 1);
            std::fprintf(f, "\n");
        }
    }
    std::fclose(f);
}

struct Args {
    const char* input = nullptr;
    const char* output = nullptr;
    int levels = 1;
    int repeat = 1;
    bool corners = false;
    bool limit = false;  // OpenSubdiv drivers: write the limit positions of the finest level
    bool normals = true; // with --limit: also the limit normals (--no-normals: positions only)
    bool uniform_creasing = false;  // OpenSubdiv drivers: --creasing uniform (default chaikin)
    bool smooth_triangles = false;  // osd_catmark: --triangles smooth (TRI_SUB_SMOOTH; default catmark)
    bool no_boundary = false;       // OpenSubdiv drivers: --boundary-none (VTX_BOUNDARY_NONE)
    std::string scheme;  // drivers of several schemes: the one of --scheme (default the first)
};

// The common command line; `schemes` lists the values --scheme takes (none: no --scheme).
inline Args parse_args(int argc, char** argv, const char* usage, bool has_corners,
                       const std::vector<std::string>& schemes = {}) {
    Args a;
    if (!schemes.empty()) a.scheme = schemes[0];
    bool scheme_ok = true;
    for (int i = 1; i < argc; ++i) {
        std::string s = argv[i];
        if (s == "-n" && i + 1 < argc) a.levels = std::atoi(argv[++i]);
        else if (s == "--scheme" && !schemes.empty() && i + 1 < argc) {
            a.scheme = argv[++i];
            scheme_ok = std::find(schemes.begin(), schemes.end(), a.scheme) != schemes.end();
        }
        else if (s == "--repeat" && i + 1 < argc) a.repeat = std::atoi(argv[++i]);
        else if (s == "-o" && i + 1 < argc) a.output = argv[++i];
        else if (s == "--corners" && has_corners) a.corners = true;
        else if (s == "--limit" && has_corners) a.limit = true;
        else if (s == "--no-normals" && has_corners) a.normals = false;
        else if (s == "--creasing" && has_corners && i + 1 < argc) {
            std::string m = argv[++i];
            scheme_ok = scheme_ok && (m == "uniform" || m == "chaikin");
            a.uniform_creasing = m == "uniform";
        }
        else if (s == "--triangles" && has_corners && i + 1 < argc) {
            std::string m = argv[++i];
            scheme_ok = scheme_ok && (m == "catmark" || m == "smooth");
            a.smooth_triangles = m == "smooth";
        }
        else if (s == "--boundary-none" && has_corners) a.no_boundary = true;
        else if (s == "--json") {
        }  // always JSON
        else if (!a.input && s[0] != '-') a.input = argv[i];
        else {
            std::fprintf(stderr, "usage: %s\n", usage);
            std::exit(2);
        }
    }
    if (!a.input || a.levels < 0 || a.repeat < 1 || !scheme_ok) {
        std::fprintf(stderr, "usage: %s\n", usage);
        std::exit(2);
    }
    return a;
}

inline double now_seconds() {
    using namespace std::chrono;
    return duration<double>(steady_clock::now().time_since_epoch()).count();
}

inline double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// The same JSON line as `splinekit subdivide --json`, plus every repeat's time.
inline void print_json(long vertices, long faces, const std::vector<double>& times) {
    std::printf("{\"vertices\": %ld, \"faces\": %ld, \"seconds\": %.6f, \"all_seconds\": [", vertices, faces,
                median(times));
    for (size_t i = 0; i < times.size(); ++i) std::printf("%s%.6f", i ? ", " : "", times[i]);
    std::printf("]}\n");
}
