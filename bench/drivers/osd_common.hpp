// The OpenSubdiv drivers' shared part: uniform refinement with Far and double-precision
// primvar interpolation, timed per repeat; the input's crease and corner tags given to the
// TopologyDescriptor (creasing method CREASE_CHAIKIN, or CREASE_UNIFORM with --creasing uniform);
// boundary interpolation VTX_BOUNDARY_EDGE_ONLY, EDGE_AND_CORNER with --corners or NONE with
// --boundary-none (its hole faces are not written; every vertex is); triangle subdivision
// TRI_SUB_CATMARK or TRI_SUB_SMOOTH with --triangles smooth; the finest level written as OBJ (with --limit: its
// limit positions, and as `vn` the unit limit normals, the normalized cross product of the two
// limit tangents of PrimvarRefinerReal::Limit).
#pragma once

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/version.h>

#include <cmath>
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

// Refines `in` (faces of `in.sizes` corners, or triangles) `a.levels` times with `scheme`,
// `a.repeat` times; writes the finest level to `a.output` if given and prints the JSON line.
inline int run_osd(const Args& a, Tri in, Sdc::SchemeType scheme, const char* scheme_name) {
    if (in.sizes.empty()) in.sizes.assign(in.num_faces(), 3);
    typedef Far::TopologyDescriptor Descriptor;
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(a.no_boundary ? Sdc::Options::VTX_BOUNDARY_NONE
                                    : a.corners   ? Sdc::Options::VTX_BOUNDARY_EDGE_AND_CORNER
                                                  : Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    sdc.SetCreasingMethod(a.uniform_creasing ? Sdc::Options::CREASE_UNIFORM : Sdc::Options::CREASE_CHAIKIN);
    sdc.SetTriangleSubdivision(a.smooth_triangles ? Sdc::Options::TRI_SUB_SMOOTH : Sdc::Options::TRI_SUB_CATMARK);

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
        desc.numVertsPerFace = in.sizes.data();
        desc.vertIndicesPerFace = in.tri.data();
        desc.numCreases = int(in.crease_sharpness.size());
        desc.creaseVertexIndexPairs = in.crease_pairs.data();
        desc.creaseWeights = in.crease_sharpness.data();
        desc.numCorners = int(in.corner_sharpness.size());
        desc.cornerVertexIndices = in.corner_vertices.data();
        desc.cornerWeights = in.corner_sharpness.data();
        refiner.reset(Far::TopologyRefinerFactory<Descriptor>::Create(
            desc, Far::TopologyRefinerFactory<Descriptor>::Options(scheme, sdc)));
        if (!refiner) {
            std::fprintf(stderr, "OpenSubdiv refused the topology\n");
            return 1;
        }
        Far::TopologyRefiner::UniformOptions uniform(a.levels);
        uniform.fullTopologyInLastLevel = a.limit;  // Limit() needs it
        refiner->RefineUniform(uniform);
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
        if (a.limit) {
            // the limit positions of the finest level's vertices, and the unit limit normals
            // tan1 x tan2 (not timed)
            // (--no-normals: positions only. Limit with tangents overruns its mask buffers at
            // a non-manifold Catmull-Clark vertex of many faces, such as the ends of an edge of
            // 100 faces; the positions-only Limit does not.)
            std::vector<Vertex> limit(nv), tan1(nv), tan2(nv);
            if (a.normals) {
                Far::PrimvarRefinerReal<double>(*refiner).Limit(&buffer[first], limit, tan1, tan2);
            } else {
                Far::PrimvarRefinerReal<double>(*refiner).Limit(&buffer[first], limit);
            }
            std::memcpy(out.xyz.data(), limit.data(), 3 * nv * sizeof(double));
            for (long v = 0; a.normals && v < nv; ++v) {
                const double* s = tan1[v].p;
                const double* t = tan2[v].p;
                double n[3] = {s[1] * t[2] - s[2] * t[1], s[2] * t[0] - s[0] * t[2], s[0] * t[1] - s[1] * t[0]};
                double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                for (double x : n) out.nxyz.push_back(len > 0 ? x / len : 0.0);
            }
        } else {
            std::memcpy(out.xyz.data(), &buffer[first], 3 * nv * sizeof(double));
        }
        bool triangles = true;
        for (int f = 0; f < nf; ++f) {
            if (last.IsFaceHole(f)) continue;  // VTX_BOUNDARY_NONE: faces at the boundary are holes
            Far::ConstIndexArray fv = last.GetFaceVertices(f);
            out.sizes.push_back(fv.size());
            triangles = triangles && fv.size() == 3;
            for (int k = 0; k < fv.size(); ++k) out.tri.push_back(fv[k]);
        }
        if (triangles) out.sizes.clear();  // the triangle form of write_obj
        char comment[512];
        std::snprintf(comment, sizeof comment, "OpenSubdiv %d.%d.%d Far, %s, %s%s, RefineUniform(%d), PrimvarRefinerReal<double>%s%s",
                      OPENSUBDIV_VERSION_MAJOR, OPENSUBDIV_VERSION_MINOR, OPENSUBDIV_VERSION_PATCH, scheme_name,
                      a.no_boundary ? "VTX_BOUNDARY_NONE (hole faces left out)"
                      : a.corners   ? "VTX_BOUNDARY_EDGE_AND_CORNER"
                                    : "VTX_BOUNDARY_EDGE_ONLY",
                      a.smooth_triangles ? ", TRI_SUB_SMOOTH" : "", a.levels,
                      a.limit ? ", Limit" : "",
                      in.crease_sharpness.empty() && in.corner_sharpness.empty() ? ""
                      : a.uniform_creasing ? ", creases CREASE_UNIFORM" : ", creases CREASE_CHAIKIN");
        write_obj(a.output, out, comment);
    }
    print_json(nv, nf, times);
    return 0;
}
