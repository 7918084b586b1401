// OpenSubdiv (Far) Catmull-Clark subdivision driver.
//
//   osd_catmark IN.obj -n LEVELS [--scheme catmark|bilinear] [--repeat R] [--corners | --boundary-none]
//               [--triangles catmark|smooth] [--limit [--no-normals]] [-o OUT.obj]
//
// --limit writes the limit positions (PrimvarRefinerReal::Limit) of the finest level instead.
//
// Catmull-Clark scheme (Sdc::SCHEME_CATMARK) on any polygon mesh, boundary interpolation
// VTX_BOUNDARY_EDGE_ONLY (boundary edges are sharp creases), or VTX_BOUNDARY_EDGE_AND_CORNER
// with --corners (one-face corners stay fixed), or VTX_BOUNDARY_NONE with --boundary-none (faces
// at the boundary are holes: left out of the output); --triangles smooth is TRI_SUB_SMOOTH (the
// edge points of an edge with a triangle on either side). --scheme bilinear refines with
// Sdc::SCHEME_BILINEAR instead (every n-gon into n quads at its centroid and edge midpoints).
// Other Sdc options default. Uniform refinement
// to LEVELS, then PrimvarRefinerReal<double> interpolates double-precision positions level by
// level. Timed: TopologyRefinerFactory::Create, RefineUniform and the interpolation, per
// repeat; not timed: reading and writing files. Writes the finest level's quads.
// Prints {"vertices": V, "faces": F, "seconds": median, "all_seconds": [...]}.

#include "osd_common.hpp"

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv,
                        "osd_catmark IN.obj -n LEVELS [--scheme catmark|bilinear] [--repeat R] [--corners | --boundary-none] "
                        "[--triangles catmark|smooth] [--limit [--no-normals]] [--creasing chaikin|uniform] [-o OUT.obj]",
                        true, {"catmark", "bilinear"});
    if (a.scheme == "bilinear") return run_osd(a, read_obj(a.input, true), Sdc::SCHEME_BILINEAR, "SCHEME_BILINEAR");
    return run_osd(a, read_obj(a.input, true), Sdc::SCHEME_CATMARK, "SCHEME_CATMARK");
}
