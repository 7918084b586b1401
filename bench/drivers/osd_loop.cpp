// OpenSubdiv (Far) Loop subdivision driver.
//
//   osd_loop IN.obj -n LEVELS [--repeat R] [--corners] [-o OUT.obj]
//
// Loop scheme (Sdc::SCHEME_LOOP), boundary interpolation VTX_BOUNDARY_EDGE_ONLY (boundary
// edges are sharp creases: midpoint odd vertices, 3/4 1/8 1/8 even vertices, one-face corners
// smoothed like any boundary vertex), or VTX_BOUNDARY_EDGE_AND_CORNER with --corners (one-face
// corners stay fixed). Other Sdc options default. Uniform refinement to LEVELS, then
// PrimvarRefinerReal<double> interpolates double-precision positions level by level (double
// weights too). Timed: TopologyRefinerFactory::Create from a face-vertex TopologyDescriptor,
// RefineUniform and the interpolation, per repeat; not timed: reading and writing files.
// Prints {"vertices": V, "faces": F, "seconds": median, "all_seconds": [...]}.

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/version.h>

#include <memory>

#include "common.hpp"

using namespace OpenSubdiv;

struct Vertex {
    double p[3];
    void Clear(void* = nullptr) { p[0] = p[1] = p[2] = 0.0; }
    void AddWithWeight(Vertex const& s, double w) {
        p[0] += w * s.p[0];
        p[1] += w * s.p[1];
        p[2] += w * s.p[2];
    }
};

int main(int argc, char** argv) {
    Args a = parse_args(argc, argv, "osd_loop IN.obj -n LEVELS [--repeat R] [--corners] [-o OUT.obj]", true);
    Tri in = read_obj(a.input);
    std::vector<int> verts_per_face(in.num_faces(), 3);

    typedef Far::TopologyDescriptor Descriptor;
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(a.corners ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                              : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);

    std::vector<double> times;
    std::unique_ptr<Far::TopologyRefiner> refiner;
    std::vector<Vertex> buffer;
    for (int r = 0; r < a.repeat; ++r) {
        refiner.reset();
        buffer = std::vector<Vertex>();
        double t0 = now_seconds();
        Descriptor desc;
        desc.numVertices = in.num_vertices();
        desc.numFaces = in.num_faces();
        desc.numVertsPerFace = verts_per_face.data();
        desc.vertIndicesPerFace = in.tri.data();
        refiner.reset(Far::TopologyRefinerFactory<Descriptor>::Create(
            desc, Far::TopologyRefinerFactory<Descriptor>::Options(Sdc::SCHEME_LOOP, sdc)));
        if (!refiner) {
            std::fprintf(stderr, "OpenSubdiv refused the topology\n");
            return 1;
        }
        refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(a.levels));
        buffer.resize(refiner->GetNumVerticesTotal());
        std::memcpy(buffer.data(), in.xyz.data(), in.xyz.size() * sizeof(double));
        Far::PrimvarRefinerReal<double> primvar(*refiner);
        Vertex* src = buffer.data();
        for (int level = 1; level <= a.levels; ++level) {
            Vertex* dst = src + refiner->GetLevel(level - 1).GetNumVertices();
            primvar.Interpolate(level, src, dst);
            src = dst;
        }
        times.push_back(now_seconds() - t0);
    }

    Far::TopologyLevel const& last = refiner->GetLevel(a.levels);
    long nv = last.GetNumVertices(), nf = last.GetNumFaces();
    if (a.output) {
        Tri out;
        size_t first = buffer.size() - size_t(nv);
        out.xyz.resize(3 * nv);
        std::memcpy(out.xyz.data(), &buffer[first], 3 * nv * sizeof(double));
        out.tri.reserve(3 * nf);
        for (int f = 0; f < nf; ++f) {
            Far::ConstIndexArray fv = last.GetFaceVertices(f);
            if (fv.size() != 3) return 1;
            for (int k = 0; k < 3; ++k) out.tri.push_back(fv[k]);
        }
        char comment[512];
        std::snprintf(comment, sizeof comment,
                      "OpenSubdiv %d.%d.%d Far, SCHEME_LOOP, %s, RefineUniform(%d), PrimvarRefinerReal<double>",
                      OPENSUBDIV_VERSION_MAJOR, OPENSUBDIV_VERSION_MINOR, OPENSUBDIV_VERSION_PATCH,
                       a.corners ? "VTX_BOUNDARY_EDGE_AND_CORNER" : "VTX_BOUNDARY_EDGE_ONLY",
                      a.levels);
        write_obj(a.output, out, comment);
    }
    print_json(nv, nf, times);
    return 0;
}
