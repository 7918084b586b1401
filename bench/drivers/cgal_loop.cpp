// CGAL Loop subdivision driver.
//
//   cgal_loop IN.obj -n LEVELS [--repeat R] [-o OUT.obj]
//
// CGAL::Subdivision_method_3::Loop_subdivision(mesh, parameters::number_of_iterations(LEVELS))
// on a CGAL::Surface_mesh<Simple_cartesian<double>::Point_3>: Loop's beta, boundary edges
// midpoint, boundary vertices (v_prev + 6 v + v_next) / 8, corners not fixed. Timed: the call
// alone, per repeat, on a fresh copy of the input mesh (the copy is not timed); not timed:
// building the mesh from the file and writing files.

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>
#include <CGAL/version.h>

#include "common.hpp"

typedef CGAL::Simple_cartesian<double> Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv, "cgal_loop IN.obj -n LEVELS [--repeat R] [-o OUT.obj]", false);
    Tri in = read_obj(a.input);
    Mesh base;
    std::vector<Mesh::Vertex_index> vi;
    for (int v = 0; v < in.num_vertices(); ++v)
        vi.push_back(base.add_vertex(Point(in.xyz[3 * v], in.xyz[3 * v + 1], in.xyz[3 * v + 2])));
    for (int t = 0; t < in.num_faces(); ++t) {
        if (base.add_face(vi[in.tri[3 * t]], vi[in.tri[3 * t + 1]], vi[in.tri[3 * t + 2]]) == Mesh::null_face()) {
            std::fprintf(stderr, "CGAL refused face %d\n", t);
            return 1;
        }
    }

    std::vector<double> times;
    Mesh m;
    for (int r = 0; r < a.repeat; ++r) {
        m = Mesh();
        m = base;
        double t0 = now_seconds();
        CGAL::Subdivision_method_3::Loop_subdivision(m, CGAL::parameters::number_of_iterations(a.levels));
        times.push_back(now_seconds() - t0);
    }

    if (a.output) {
        Tri out;
        std::vector<int> index(m.number_of_vertices() + m.number_of_removed_vertices(), -1);
        int k = 0;
        for (auto v : m.vertices()) {
            index[v.idx()] = k++;
            const Point& p = m.point(v);
            out.xyz.insert(out.xyz.end(), {p.x(), p.y(), p.z()});
        }
        for (auto f : m.faces()) {
            int c = 0;
            for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
                out.tri.push_back(index[v.idx()]);
                ++c;
            }
            if (c != 3) return 1;
        }
        char comment[256];
        std::snprintf(comment, sizeof comment, "CGAL %s Subdivision_method_3::Loop_subdivision, number_of_iterations(%d)",
                      CGAL_VERSION_STR, a.levels);
        write_obj(a.output, out, comment);
    }
    print_json(long(m.number_of_vertices()), long(m.number_of_faces()), times);
    return 0;
}
