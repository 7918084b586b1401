// OpenSubdiv (Far) Catmull-Clark subdivision driver.
//
//   osd_catmark IN.obj -n LEVELS [--repeat R] [--corners] [--limit [--no-normals]] [-o OUT.obj]
//
// --limit writes the limit positions (PrimvarRefinerReal::Limit) of the finest level instead.
//
// Catmull-Clark scheme (Sdc::SCHEME_CATMARK) on any polygon mesh, boundary interpolation
// VTX_BOUNDARY_EDGE_ONLY (boundary edges are sharp creases), or VTX_BOUNDARY_EDGE_AND_CORNER
// with --corners (one-face corners stay fixed). Other Sdc options default. Uniform refinement
// to LEVELS, then PrimvarRefinerReal<double> interpolates double-precision positions level by
// level. Timed: TopologyRefinerFactory::Create, RefineUniform and the interpolation, per
// repeat; not timed: reading and writing files. Writes the finest level's quads.
// Prints {"vertices": V, "faces": F, "seconds": median, "all_seconds": [...]}.

#include "osd_common.hpp"

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv, "osd_catmark IN.obj -n LEVELS [--repeat R] [--corners] [--limit [--no-normals]] [--creasing chaikin|uniform] [-o OUT.obj]", true);
    return run_osd(a, read_obj(a.input, true), Sdc::SCHEME_CATMARK, "SCHEME_CATMARK");
}
