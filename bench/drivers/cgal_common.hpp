// Shared helpers of the CGAL drivers: a CGAL::Surface_mesh from the OBJ reader's mesh, and back.
#pragma once

#include <CGAL/Surface_mesh.h>

#include "common.hpp"

// Adds the vertices and faces of `in` to the empty `mesh`; exits with a message naming the
// first face CGAL refuses (non-manifold or inconsistently oriented).
template <class Mesh>
void to_surface_mesh(const Tri& in, Mesh& mesh) {
    using Point = typename Mesh::Point;
    std::vector<typename Mesh::Vertex_index> vi;
    for (int v = 0; v < in.num_vertices(); ++v)
        vi.push_back(mesh.add_vertex(Point(in.xyz[3 * v], in.xyz[3 * v + 1], in.xyz[3 * v + 2])));
    size_t c = 0;
    std::vector<typename Mesh::Vertex_index> face;
    for (int f = 0; f < in.num_faces(); ++f) {
        const int n = in.sizes.empty() ? 3 : in.sizes[f];
        face.clear();
        for (int k = 0; k < n; ++k) face.push_back(vi[in.tri[c++]]);
        if (mesh.add_face(face) == Mesh::null_face()) {
            std::fprintf(stderr, "CGAL refused face %d\n", f);
            std::exit(1);
        }
    }
}

// The vertices (in CGAL's order, removed ones skipped) and faces of `mesh`; `sizes` is filled
// unless every face is a triangle.
template <class Mesh>
Tri from_surface_mesh(const Mesh& m) {
    Tri out;
    std::vector<int> index(m.number_of_vertices() + m.number_of_removed_vertices(), -1);
    int k = 0;
    for (auto v : m.vertices()) {
        index[v.idx()] = k++;
        const auto& p = m.point(v);
        out.xyz.insert(out.xyz.end(), {p.x(), p.y(), p.z()});
    }
    bool triangles = true;
    for (auto f : m.faces()) {
        int n = 0;
        for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
            out.tri.push_back(index[v.idx()]);
            ++n;
        }
        out.sizes.push_back(n);
        triangles = triangles && n == 3;
    }
    if (triangles) out.sizes.clear();
    return out;
}
