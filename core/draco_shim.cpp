// The only C++ in jade: libdraco 1.5.5 has no C API.
#include "draco_shim.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <string>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <utility>
#include <vector>

#ifdef JD_HAVE_MESHOPT
#include <meshoptimizer.h>
#endif

#include <draco/compression/decode.h>
#include <draco/io/obj_decoder.h>
#include <draco/io/ply_decoder.h>
#include <draco/io/stl_decoder.h>
#include <draco/mesh/mesh.h>

#include "mesh_format.h"

namespace {

const char *format_name(int format)
{
    switch (format) {
    case JD_FORMAT_OBJ: return "OBJ reader";
    case JD_FORMAT_PLY: return "PLY reader";
    case JD_FORMAT_STL: return "STL reader";
    default: return "draco";
    }
}

void set_err(char *err, size_t errlen, const char *msg)
{
    if (err && errlen)
        std::snprintf(err, errlen, "%s", msg);
}

// Buffers rows so the pipe sees few large writes.
struct Out {
    Out(jd_draco_write_fn w, void *u) : write(w), user(u) {}
    jd_draco_write_fn write;
    void *user;
    unsigned char buf[1 << 16];
    size_t n = 0;
    bool ok = true;
    void put(const void *p, size_t len)
    {
        const unsigned char *s = static_cast<const unsigned char *>(p);
        while (ok && len) {
            size_t k = sizeof buf - n < len ? sizeof buf - n : len;
            std::memcpy(buf + n, s, k);
            n += k; s += k; len -= k;
            if (n == sizeof buf) flush();
        }
    }
    void flush()
    {
        if (ok && n && write(user, buf, n) != 0) ok = false;
        n = 0;
    }
};

// Streams one attribute as `comps` floats per point; missing components are 0.
bool put_attribute(Out &out, const draco::PointAttribute *att, uint32_t nv, int comps)
{
    float v[4];
    for (uint32_t i = 0; i < nv; ++i) {
        draco::AttributeValueIndex avi = att->mapped_index(draco::PointIndex(i));
        // A hostile file can map a point past the attribute's values.
        if (avi.value() >= att->size()) return false;
        std::memset(v, 0, sizeof v);
        if (!att->ConvertValue<float>(avi, static_cast<int8_t>(comps), v)) return false;
        out.put(v, sizeof(float) * comps);
    }
    return true;
}

// The triangles in the order a GPU draws best: meshoptimizer's vertex cache
// order (fewer vertex shader runs), then its overdraw order (fewer pixels
// shaded twice, for up to 5% more vertex work). Done here, in the decoder's
// child process, where the heap is allowed: the parent keeps its one
// allocation. Indices past the vertex count (a hostile file) leave the
// order alone; the parent refuses them anyway.
void order_for_gpu(std::vector<uint32_t> &idx, const draco::PointAttribute *pos, uint32_t nv)
{
#ifdef JD_HAVE_MESHOPT
    for (uint32_t i : idx)
        if (i >= nv) return;
    std::vector<float> p(3 * size_t(nv));
    for (uint32_t i = 0; i < nv; ++i) {
        draco::AttributeValueIndex avi = pos->mapped_index(draco::PointIndex(i));
        if (avi.value() >= pos->size()) return;
        float v[3] = {0, 0, 0};
        if (!pos->ConvertValue<float>(avi, 3, v)) return;
        for (int k = 0; k < 3; ++k) p[3 * size_t(i) + k] = std::isfinite(v[k]) ? v[k] : 0.0f;
    }
    // The overdraw order sorts by which way triangles face: a mesh wound
    // inside out (the parent turns it round later) is ordered turned round.
    double vol6 = 0;
    for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        const float *a = &p[3 * size_t(idx[t])], *b = &p[3 * size_t(idx[t + 1])], *c = &p[3 * size_t(idx[t + 2])];
        vol6 += a[0] * (double(b[1]) * c[2] - double(b[2]) * c[1]) - a[1] * (double(b[0]) * c[2] - double(b[2]) * c[0]) +
                a[2] * (double(b[0]) * c[1] - double(b[1]) * c[0]);
    }
    auto turn = [&idx]() {
        for (size_t t = 0; t + 2 < idx.size(); t += 3) std::swap(idx[t + 1], idx[t + 2]);
    };
    if (vol6 < 0) turn();
    std::vector<uint32_t> tmp(idx.size());
    meshopt_optimizeVertexCache(tmp.data(), idx.data(), idx.size(), nv);
    meshopt_optimizeOverdraw(idx.data(), tmp.data(), idx.size(), p.data(), nv, 3 * sizeof(float), 1.05f);
    if (vol6 < 0) turn(); // the file's winding: the parent decides what to do with it
#else
    (void)idx;
    (void)pos;
    (void)nv;
#endif
}

// libdraco 1.5.5 reads binary STL only: ASCII STL ("solid", then "facet
// normal", "outer loop", three "vertex x y z", "endloop", "endfacet") is
// rewritten as binary first. Anything else in the text is an error.
bool ascii_stl_to_binary(const char *text, size_t n, std::vector<char> &out)
{
    std::string s(text, n);
    out.assign(84, 0);
    uint32_t count = 0;
    size_t at = 0;
    auto word = [&](std::string &w) {
        while (at < s.size() && std::isspace(static_cast<unsigned char>(s[at]))) at++;
        size_t b = at;
        while (at < s.size() && !std::isspace(static_cast<unsigned char>(s[at]))) at++;
        w = s.substr(b, at - b);
        return !w.empty();
    };
    auto number = [&](float &v) {
        std::string w;
        if (!word(w)) return false;
        char *end;
        v = std::strtof(w.c_str(), &end);
        return *end == 0;
    };
    std::string w;
    if (!word(w) || w != "solid") return false;
    while (word(w)) {
        if (w == "endsolid") break;
        if (w != "facet") continue; // the solid's name
        float tri[12];
        std::string a, b;
        if (!word(a) || a != "normal" || !number(tri[0]) || !number(tri[1]) || !number(tri[2])) return false;
        if (!word(a) || a != "outer" || !word(b) || b != "loop") return false;
        for (int k = 0; k < 3; ++k)
            if (!word(a) || a != "vertex" || !number(tri[3 + 3 * k]) || !number(tri[4 + 3 * k]) ||
                !number(tri[5 + 3 * k]))
                return false;
        if (!word(a) || a != "endloop" || !word(b) || b != "endfacet") return false;
        const char *bytes = reinterpret_cast<const char *>(tri);
        out.insert(out.end(), bytes, bytes + sizeof tri);
        out.insert(out.end(), 2, 0); // attribute byte count
        if (++count == 0) return false;
    }
    std::memcpy(&out[80], &count, 4);
    return count > 0;
}

// libdraco's readers: its own format, and OBJ, PLY and STL through its io
// library. A failure comes back with the reader's message.
std::unique_ptr<draco::Mesh> read_mesh(draco::DecoderBuffer *buffer, int format, char *err, size_t errlen)
{
    draco::Status status;
    std::unique_ptr<draco::Mesh> mesh;
    if (format == JD_FORMAT_OBJ || format == JD_FORMAT_PLY) {
        mesh.reset(new draco::Mesh());
        status = format == JD_FORMAT_OBJ ? draco::ObjDecoder().DecodeFromBuffer(buffer, mesh.get())
                                         : draco::PlyDecoder().DecodeFromBuffer(buffer, mesh.get());
    } else if (format == JD_FORMAT_STL) {
        std::vector<char> binary;
        draco::DecoderBuffer converted;
        const char *d = buffer->data_head();
        size_t n = static_cast<size_t>(buffer->remaining_size());
        bool is_binary = n >= 84 && uint64_t(uint32_t(uint8_t(d[80])) | uint32_t(uint8_t(d[81])) << 8 |
                                             uint32_t(uint8_t(d[82])) << 16 | uint32_t(uint8_t(d[83])) << 24) *
                                                    50 + 84 == n;
        if (is_binary) {
            // Many binary STLs' 80-byte headers begin "solid", which libdraco
            // takes for ASCII: the header carries nothing jade needs.
            binary.assign(d, d + n);
            std::memset(binary.data(), ' ', 80);
        } else if (!ascii_stl_to_binary(d, n, binary)) {
            set_err(err, errlen, "STL reader could not decode it: not a well-formed ASCII STL");
            return nullptr;
        }
        converted.Init(binary.data(), binary.size());
        buffer = &converted;
        auto result = draco::StlDecoder().DecodeFromBuffer(buffer);
        status = result.status();
        if (result.ok()) mesh = std::move(result).value();
    } else {
        auto result = draco::Decoder().DecodeMeshFromBuffer(buffer);
        status = result.status();
        if (result.ok()) mesh = std::move(result).value();
    }
    if (!status.ok() || !mesh) {
        char msg[256];
        std::snprintf(msg, sizeof msg, "%s could not decode it: %s", format_name(format), status.error_msg());
        set_err(err, errlen, msg);
        return nullptr;
    }
    if (format == JD_FORMAT_STL) {
        // STL repeats every corner with its facet's normal: without them,
        // shared corners merge and jade computes smooth normals.
        const draco::PointAttribute *n = mesh->GetNamedAttribute(draco::GeometryAttribute::NORMAL);
        if (n) mesh->DeleteAttribute(mesh->GetNamedAttributeId(draco::GeometryAttribute::NORMAL));
        mesh->DeduplicateAttributeValues();
        mesh->DeduplicatePointIds();
    }
    return mesh;
}

int decode(const void *data, size_t size, int format, uint32_t max_vertices, uint32_t max_faces, int keep_order,
           jd_draco_write_fn write, void *user, char *err, size_t errlen)
{
    draco::DecoderBuffer buffer;
    buffer.Init(static_cast<const char *>(data), size);
    std::unique_ptr<draco::Mesh> mesh = read_mesh(&buffer, format, err, errlen);
    if (!mesh) return -1;
    const uint32_t nv = mesh->num_points();
    const uint32_t nf = mesh->num_faces();
    if (nv == 0 || nf == 0) {
        set_err(err, errlen, "the mesh is empty (no vertices or no faces)");
        return -1;
    }
    if (nv > max_vertices || nf > max_faces) {
        char msg[160];
        std::snprintf(msg, sizeof msg, "decoded %u vertices and %u faces, over the limit of %u / %u",
                      nv, nf, max_vertices, max_faces);
        set_err(err, errlen, msg);
        return -1;
    }
    const draco::PointAttribute *pos = mesh->GetNamedAttribute(draco::GeometryAttribute::POSITION);
    if (!pos || pos->num_components() < 2) {
        set_err(err, errlen, "the mesh has no usable position attribute");
        return -1;
    }
    const draco::PointAttribute *nrm = mesh->GetNamedAttribute(draco::GeometryAttribute::NORMAL);
    if (nrm && nrm->num_components() != 3) nrm = nullptr;
    const draco::PointAttribute *uv = mesh->GetNamedAttribute(draco::GeometryAttribute::TEX_COORD);
    if (uv && uv->num_components() < 2) uv = nullptr;

    std::unique_ptr<Out> out(new Out(write, user));
    jd_draco_record_header h = {JD_DRACO_RECORD_MAGIC, nv, nf,
                                (nrm ? uint32_t(JD_DRACO_HAS_NORMALS) : 0u) |
                                    (uv ? uint32_t(JD_DRACO_HAS_UVS) : 0u)};
    out->put(&h, sizeof h);
    if (!put_attribute(*out, pos, nv, 3) || (nrm && !put_attribute(*out, nrm, nv, 3)) ||
        (uv && !put_attribute(*out, uv, nv, 2))) {
        set_err(err, errlen, "an attribute maps a vertex to a value that does not exist");
        return -1;
    }
    std::vector<uint32_t> idx(3 * size_t(nf));
    for (uint32_t f = 0; f < nf; ++f) {
        const draco::Mesh::Face &face = mesh->face(draco::FaceIndex(f));
        for (int k = 0; k < 3; ++k) idx[3 * size_t(f) + k] = face[k].value();
    }
    if (!keep_order) {
        // Ordering is a nicety: a mesh near the child's memory limit keeps
        // its file order rather than failing to load.
        std::vector<uint32_t> file_order;
        try {
            file_order = idx;
            order_for_gpu(idx, pos, nv);
        } catch (const std::bad_alloc &) {
            if (file_order.size() == idx.size()) idx.swap(file_order);
        }
    }
    out->put(idx.data(), sizeof(uint32_t) * idx.size());
    out->flush();
    if (!out->ok) {
        set_err(err, errlen, "could not hand the decoded mesh back (pipe closed)");
        return -1;
    }
    return 0;
}

} // namespace

extern "C" int jd_draco_decode(const void *data, size_t size, int format, uint32_t max_vertices,
                               uint32_t max_faces, int keep_order, jd_draco_write_fn write, void *user,
                               char *err, size_t errlen)
{
    try {
        return decode(data, size, format, max_vertices, max_faces, keep_order, write, user, err, errlen);
    } catch (const std::bad_alloc &) {
        set_err(err, errlen, "draco ran out of memory while decoding");
    } catch (const std::exception &e) {
        char msg[200];
        std::snprintf(msg, sizeof msg, "draco threw: %s", e.what());
        set_err(err, errlen, msg);
    } catch (...) {
        set_err(err, errlen, "draco threw an unknown exception");
    }
    return -1;
}
