// OpenMesh Loop subdivision driver.
//
//   openmesh_loop IN.obj -n LEVELS [--repeat R] [-o OUT.obj]
//
// OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> on a TriMesh_ArrayKernelT with Vec3d
// points: Loop's beta, boundary edges midpoint, boundary vertices (v_l + 6 v + v_r) / 8,
// corners not fixed. Timed: attach, operator()(LEVELS) and detach, per repeat, on a fresh copy
// of the input mesh (the copy is not timed); not timed: building the mesh, files.

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/System/config.h>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>

#include "common.hpp"

struct Traits : public OpenMesh::DefaultTraits {
    typedef OpenMesh::Vec3d Point;
    typedef OpenMesh::Vec3d Normal;
};
typedef OpenMesh::TriMesh_ArrayKernelT<Traits> Mesh;

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv, "openmesh_loop IN.obj -n LEVELS [--repeat R] [-o OUT.obj]", false);
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
        double t0 = now_seconds();
        OpenMesh::Subdivider::Uniform::LoopT<Mesh, double> loop;
        loop.attach(m);
        loop(size_t(a.levels));
        loop.detach();
        times.push_back(now_seconds() - t0);
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
        std::snprintf(comment, sizeof comment, "OpenMesh %d.%d Subdivider::Uniform::LoopT<Mesh, double>(%d)",
                      OM_GET_VER, OM_GET_MAJ, a.levels);
        write_obj(a.output, out, comment);
    }
    print_json(long(m.n_vertices()), long(m.n_faces()), times);
    return 0;
}
