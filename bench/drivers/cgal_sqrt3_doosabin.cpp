// CGAL √3 and Doo-Sabin subdivision driver.
//
//   cgal_sqrt3_doosabin IN.obj -n LEVELS [--scheme sqrt3|doo-sabin] [--repeat R] [-o OUT.obj]
//
// CGAL::Subdivision_method_3::Sqrt3_subdivision (triangle meshes) or DooSabin_subdivision (any
// polygon mesh) with number_of_iterations(LEVELS), on a CGAL::Surface_mesh<Epick::Point_3>:
//  - √3 (Kobbelt): a centroid per face, old interior vertices (1 − α)p + α/n Σ neighbours with
//    α = (4 − 2cos(2π/n))/9, old edges flipped; boundaries are refined only on the 2nd, 4th, …
//    step of one call (two points per boundary edge, (p₋ + 16s + 10t)/27 and (10s + 16t + t₊)/27,
//    boundary vertices (4p₋ + 19s + 4t)/27), and stay as they are on the other steps;
//  - Doo-Sabin: one point per face corner, weights (n + 5)/(4n) for its own vertex and
//    (3 + 2cos(2πk/n))/(4n) for the one k corners further on (9, 3, 1, 3 /16 for quads); faces
//    for every face, interior edge and interior vertex, none for boundary edges and vertices.
// Output vertices and faces in CGAL's order, positions with %.17g. Timed: the call alone, per
// repeat, on a fresh copy of the input mesh; not timed: building the mesh and writing files.

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>
#include <CGAL/version.h>

#include "cgal_common.hpp"

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef Kernel::Point_3 Point;
typedef CGAL::Surface_mesh<Point> Mesh;

int main(int argc, char** argv) {
    const char* usage = "cgal_sqrt3_doosabin IN.obj -n LEVELS [--scheme sqrt3|doo-sabin] [--repeat R] [-o OUT.obj]";
    Args a = parse_args(argc, argv, usage, false, {"sqrt3", "doo-sabin"});
    const bool sqrt3 = a.scheme == "sqrt3";
    Tri in = read_obj(a.input, true);
    if (sqrt3 && !in.sizes.empty())
        for (int f = 0; f < in.num_faces(); ++f)
            if (in.sizes[f] != 3) {
                std::fprintf(stderr, "face %d is not a triangle\n", f);
                return 1;
            }
    Mesh base;
    to_surface_mesh(in, base);

    std::vector<double> times;
    Mesh m;
    for (int r = 0; r < a.repeat; ++r) {
        m = Mesh();
        m = base;
        double t0 = now_seconds();
        if (sqrt3)
            CGAL::Subdivision_method_3::Sqrt3_subdivision(m, CGAL::parameters::number_of_iterations(a.levels));
        else
            CGAL::Subdivision_method_3::DooSabin_subdivision(m, CGAL::parameters::number_of_iterations(a.levels));
        times.push_back(now_seconds() - t0);
    }

    if (a.output) {
        Tri out = from_surface_mesh(m);
        char comment[256];
        std::snprintf(comment, sizeof comment, "CGAL %s Subdivision_method_3::%s, number_of_iterations(%d)",
                      CGAL_VERSION_STR, sqrt3 ? "Sqrt3_subdivision" : "DooSabin_subdivision", a.levels);
        write_obj(a.output, out, comment);
    }
    print_json(long(m.number_of_vertices()), long(m.number_of_faces()), times);
    return 0;
}
