// OpenMesh Loop (and modified butterfly) subdivision driver.
//
//   openmesh_loop IN.obj -n LEVELS [--scheme loop|butterfly] [--repeat R] [-o OUT.obj]
//
// On a TriMesh_ArrayKernelT with Vec3d points:
//  - loop (default): OpenMesh::Subdivider::Uniform::LoopT<Mesh, double>: Loop's beta, boundary
//    edges midpoint, boundary vertices (v_l + 6 v + v_r) / 8, corners not fixed;
//  - butterfly: ModifiedButterflyT<Mesh, double> (Zorin, Schröder and Sweldens 1996):
//    interpolating; edge points by the 8-point butterfly where both ends are regular (valence
//    6) or on the boundary, wings missing at a boundary reflected; Zorin's valence-K masks
//    around irregular interior ends (averaged when both are); the 4-point rule on boundary
//    edges.
// Timed: attach, operator()(LEVELS) and detach, per repeat, on a fresh copy of the input mesh
// (the copy is not timed); not timed: building the mesh, files.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/config.h>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/ModifiedButterFlyT.hh>

#include "common.hpp"

struct Traits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
typedef OpenMesh::TriMesh_ArrayKernelT<Traits> Mesh;

template <typename Subdivider>
double run(Mesh& m, int levels) {
    double t0 = now_seconds();
    Subdivider sub;
    sub.attach(m);
    sub(size_t(levels));
    sub.detach();
    return now_seconds() - t0;
}

int main(int argc, char** argv) {
    const char* usage = "openmesh_loop IN.obj -n LEVELS [--scheme loop|butterfly] [--repeat R] [-o OUT.obj]";
    Args a = parse_args(argc, argv, usage, false, {"loop", "butterfly"});
    const bool loop = a.scheme == "loop";
    Tri in = read_obj(a.input);
    Mesh base;
    std::vector<Mesh::VertexHandle> vh;
    for (int v = 0; v < in.num_vertices(); ++v)
        vh.push_back(base.add_vertex(Mesh::Point(in.xyz[3 * v], in.xyz[3 * v + 1], in.xyz[3 * v + 2])));
    for (int t = 0; t < in.num_faces(); ++t) {
        if (!base.add_face(vh[in.tri[3 * t]], vh[in.tri[3 * t + 1]], vh[in.tri[3 * t + 2]]).is_valid()) {
            std::fprintf(stderr, "OpenMesh refused face %d\n", t);
            return 1;
        }
    }

    std::vector<double> times;
    Mesh m;
    for (int r = 0; r < a.repeat; ++r) {
        m = Mesh();
        m = base;
        times.push_back(loop ? run<OpenMesh::Subdivider::Uniform::LoopT<Mesh, double>>(m, a.levels)
                             : run<OpenMesh::Subdivider::Uniform::ModifiedButterflyT<Mesh, double>>(m, a.levels));
    }

    if (a.output) {
        Tri out;
        for (auto v : m.vertices()) {
            const Mesh::Point& p = m.point(v);
            out.xyz.insert(out.xyz.end(), {p[0], p[1], p[2]});
        }
        for (auto f : m.faces()) {
            int c = 0;
            for (auto v : m.fv_range(f)) {
                out.tri.push_back(v.idx());
                ++c;
            }
            if (c != 3) return 1;
        }
        char comment[256];
        std::snprintf(comment, sizeof comment, "OpenMesh %d.%d Subdivider::Uniform::%s<Mesh, double>(%d)",
                      OM_GET_VER, OM_GET_MAJ, loop ? "LoopT" : "ModifiedButterflyT", a.levels);
        write_obj(a.output, out, comment);
    }
    print_json(long(m.n_vertices()), long(m.n_faces()), times);
    return 0;
}
