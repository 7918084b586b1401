// OpenSubdiv (Far) Loop subdivision driver.
//
//   osd_loop IN.obj -n LEVELS [--repeat R] [--corners] [--limit [--no-normals]] [-o OUT.obj]
//
// Loop scheme (Sdc::SCHEME_LOOP), boundary interpolation VTX_BOUNDARY_EDGE_ONLY (boundary
// edges are sharp creases: midpoint odd vertices, 3/4 1/8 1/8 even vertices, one-face corners
// smoothed like any boundary vertex), or VTX_BOUNDARY_EDGE_AND_CORNER with --corners (one-face
// corners stay fixed). Other Sdc options default. Uniform refinement to LEVELS, then
// PrimvarRefinerReal<double> interpolates double-precision positions level by level (double
// weights too). Timed: TopologyRefinerFactory::Create from a face-vertex TopologyDescriptor,
// RefineUniform and the interpolation, per repeat; not timed: reading and writing files.
// Prints {"vertices": V, "faces": F, "seconds": median, "all_seconds": [...]}.

#include "osd_common.hpp"

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv, "osd_loop IN.obj -n LEVELS [--repeat R] [--corners] [--limit [--no-normals]] [--creasing chaikin|uniform] [-o OUT.obj]", true);
    return run_osd(a, read_obj(a.input), Sdc::SCHEME_LOOP, "SCHEME_LOOP");
}
