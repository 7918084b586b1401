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

#include "cgal_common.hpp"

typedef CGAL::Simple_cartesian<double> Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv, "cgal_loop IN.obj -n LEVELS [--repeat R] [-o OUT.obj]", false);
    Tri in = read_obj(a.input);
    Mesh base;
    to_surface_mesh(in, base);

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
        Tri out = from_surface_mesh(m);
        if (!out.sizes.empty()) return 1;  // Loop gives triangles only
        char comment[256];
        std::snprintf(comment, sizeof comment, "CGAL %s Subdivision_method_3::Loop_subdivision, number_of_iterations(%d)",
                      CGAL_VERSION_STR, a.levels);
        write_obj(a.output, out, comment);
    }
    print_json(long(m.number_of_vertices()), long(m.number_of_faces()), times);
    return 0;
}
