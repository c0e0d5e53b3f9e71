// The only C++ in jade: libdraco 1.5.5 has no C API.
#include "draco_shim.h"
#include "obj_check.h"
#include "ply_strips.h"
#include "texture_decode.h"

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

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
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

// One attribute as `comps` floats per point (missing components are 0)
// into a new heap array; NULL when a hostile file maps a point past the
// attribute's values.
float *copy_attribute(const draco::PointAttribute *att, uint32_t nv, int comps)
{
    float *out = static_cast<float *>(std::malloc(sizeof(float) * size_t(comps) * (nv ? nv : 1)));
    if (!out) throw std::bad_alloc();
    for (uint32_t i = 0; i < nv; ++i) {
        draco::AttributeValueIndex avi = att->mapped_index(draco::PointIndex(i));
        float v[4] = {0, 0, 0, 0};
        if (avi.value() >= att->size() || !att->ConvertValue<float>(avi, static_cast<int8_t>(comps), v)) {
            std::free(out);
            return nullptr;
        }
        std::memcpy(out + size_t(comps) * i, v, sizeof(float) * comps);
    }
    return out;
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
    char *rewritten = nullptr; // the file rewritten for libdraco: PLY strips as faces, OBJ without comments
    draco::DecoderBuffer rewritten_buffer;
    if (format == JD_FORMAT_PLY) {
        size_t faces_n = 0;
        char msg[200];
        int k = jd_ply_strips_to_faces(buffer->data_head(), static_cast<size_t>(buffer->remaining_size()), &rewritten,
                                       &faces_n, msg, sizeof msg);
        if (k < 0) {
            set_err(err, errlen, msg);
            return nullptr;
        }
        if (k > 0) {
            rewritten_buffer.Init(rewritten, faces_n);
            buffer = &rewritten_buffer;
        }
    }
    if (format == JD_FORMAT_OBJ) {
        char msg[200];
        size_t clean_n = 0;
        if (jd_obj_for_draco(buffer->data_head(), static_cast<size_t>(buffer->remaining_size()), &rewritten,
                                  &clean_n) < 0) {
            set_err(err, errlen, "out of memory for the OBJ as libdraco reads it");
            return nullptr;
        }
        if (rewritten) {
            rewritten_buffer.Init(rewritten, clean_n);
            buffer = &rewritten_buffer;
        }
        if (jd_obj_check(buffer->data_head(), static_cast<size_t>(buffer->remaining_size()), msg, sizeof msg)) {
            std::free(rewritten);
            set_err(err, errlen, msg);
            return nullptr;
        }
    }
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
    std::free(rewritten);
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

// A decoded mesh's positions, normals, texture coordinates and faces as
// plain arrays; the attributes by their glTF unique ids where ids is given.
int to_arrays(const draco::Mesh &mesh, const int *ids, uint32_t max_vertices, uint32_t max_faces, jd_mesh_arrays *out,
              char *err, size_t errlen)
{
    const uint32_t nv = mesh.num_points();
    const uint32_t nf = mesh.num_faces();
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
    auto named = [&](draco::GeometryAttribute::Type t, int k) -> const draco::PointAttribute * {
        if (!ids) return mesh.GetNamedAttribute(t);
        return ids[k] >= 0 ? mesh.GetAttributeByUniqueId(uint32_t(ids[k])) : nullptr;
    };
    const draco::PointAttribute *pos = named(draco::GeometryAttribute::POSITION, 0);
    if (!pos || pos->num_components() < 2) {
        set_err(err, errlen, "the mesh has no usable position attribute");
        return -1;
    }
    const draco::PointAttribute *nrm = named(draco::GeometryAttribute::NORMAL, 1);
    if (nrm && nrm->num_components() != 3) nrm = nullptr;
    const draco::PointAttribute *uv = named(draco::GeometryAttribute::TEX_COORD, 2);
    if (uv && uv->num_components() < 2) uv = nullptr;
    std::memset(out, 0, sizeof *out);
    out->nv = nv;
    out->nf = nf;
    out->pos = copy_attribute(pos, nv, 3);
    out->nrm = nrm ? copy_attribute(nrm, nv, 3) : nullptr;
    out->uv = uv ? copy_attribute(uv, nv, 2) : nullptr;
    // Vertex colours (PLY's red, green, blue): sRGB-encoded as scanners and
    // exporters write them, kept as the vertex's reflectance.
    const draco::PointAttribute *col = ids ? nullptr : mesh.GetNamedAttribute(draco::GeometryAttribute::COLOR);
    bool col_bad = false;
    if (col && col->num_components() >= 3) {
        float *c = copy_attribute(col, nv, 3);
        out->col = static_cast<uint8_t *>(std::malloc(4 * size_t(nv)));
        if (!out->col) {
            std::free(c);
            jd_mesh_arrays_free(out);
            throw std::bad_alloc();
        }
        bool bytes = col->data_type() == draco::DT_UINT8 || col->data_type() == draco::DT_INT8;
        for (uint32_t i = 0; c && i < nv; ++i) {
            for (int k = 0; k < 3; ++k) {
                float v = c[3 * size_t(i) + k];
                if (bytes && !col->normalized()) v /= 255.0f;
                v = std::isfinite(v) ? std::fmin(std::fmax(v, 0.0f), 1.0f) : 0.0f;
                out->col[4 * size_t(i) + k] = jd_sqrt_encode(jd_srgb_to_linear(uint8_t(v * 255.0f + 0.5f)));
            }
            out->col[4 * size_t(i) + 3] = 0;
        }
        col_bad = !c;
        std::free(c);
    }
    if (!out->pos || (nrm && !out->nrm) || (uv && !out->uv) || col_bad) {
        jd_mesh_arrays_free(out);
        set_err(err, errlen, "an attribute maps a vertex to a value that does not exist");
        return -1;
    }
    out->idx = static_cast<uint32_t *>(std::malloc(sizeof(uint32_t) * 3 * size_t(nf)));
    if (!out->idx) {
        jd_mesh_arrays_free(out);
        throw std::bad_alloc();
    }
    for (uint32_t f = 0; f < nf; ++f) {
        const draco::Mesh::Face &face = mesh.face(draco::FaceIndex(f));
        for (int k = 0; k < 3; ++k) out->idx[3 * size_t(f) + k] = face[k].value();
    }
    return 0;
}

int read_arrays(const void *data, size_t size, int format, const int *ids, uint32_t max_vertices, uint32_t max_faces,
                jd_mesh_arrays *out, char *err, size_t errlen)
{
    draco::DecoderBuffer buffer;
    buffer.Init(static_cast<const char *>(data), size);
    std::unique_ptr<draco::Mesh> mesh = read_mesh(&buffer, format, err, errlen);
    if (!mesh) return -1;
    return to_arrays(*mesh, ids, max_vertices, max_faces, out, err, errlen);
}

// A Draco file of the mesh: positions quantised to 14 bits, normals to 10,
// texture coordinates to 12 (close to draco_encoder's defaults), the
// connectivity by edgebreaker at speed 5.
int encode(const jd_mesh_arrays *m, jd_draco_write_fn write, void *user, char *err, size_t errlen)
{
    draco::Mesh mesh;
    mesh.set_num_points(m->nv);
    mesh.SetNumFaces(m->nf);
    auto add = [&](draco::GeometryAttribute::Type t, const float *v, int comps) {
        draco::GeometryAttribute ga;
        ga.Init(t, nullptr, int8_t(comps), draco::DT_FLOAT32, false, sizeof(float) * comps, 0);
        int id = mesh.AddAttribute(ga, true, m->nv);
        draco::PointAttribute *att = mesh.attribute(id);
        for (uint32_t i = 0; i < m->nv; ++i)
            att->SetAttributeValue(draco::AttributeValueIndex(i), v + size_t(comps) * i);
    };
    add(draco::GeometryAttribute::POSITION, m->pos, 3);
    if (m->nrm) add(draco::GeometryAttribute::NORMAL, m->nrm, 3);
    if (m->uv) add(draco::GeometryAttribute::TEX_COORD, m->uv, 2);
    for (uint32_t f = 0; f < m->nf; ++f) {
        draco::Mesh::Face face;
        for (int k = 0; k < 3; ++k) face[k] = draco::PointIndex(m->idx[3 * size_t(f) + k]);
        mesh.SetFace(draco::FaceIndex(f), face);
    }
    draco::Encoder enc;
    enc.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    enc.SetAttributeQuantization(draco::GeometryAttribute::NORMAL, 10);
    enc.SetAttributeQuantization(draco::GeometryAttribute::TEX_COORD, 12);
    enc.SetSpeedOptions(5, 5);
    draco::EncoderBuffer buf;
    draco::Status st = enc.EncodeMeshToBuffer(mesh, &buf);
    if (!st.ok()) {
        char msg[256];
        std::snprintf(msg, sizeof msg, "draco could not encode the mesh: %s", st.error_msg());
        set_err(err, errlen, msg);
        return -1;
    }
    if (write(user, buf.data(), buf.size()) != 0) {
        set_err(err, errlen, "could not write the encoded mesh");
        return -1;
    }
    return 0;
}

// Every C++ exception stops at this boundary.
template <class F> int guarded(char *err, size_t errlen, F f)
{
    try {
        return f();
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

} // namespace

extern "C" int jd_draco_read(const void *data, size_t size, int format, uint32_t max_vertices, uint32_t max_faces,
                             jd_mesh_arrays *out, char *err, size_t errlen)
{
    return guarded(err, errlen, [&] { return read_arrays(data, size, format, nullptr, max_vertices, max_faces, out, err, errlen); });
}

extern "C" int jd_draco_read_ids(const void *data, size_t size, const int ids[3], uint32_t max_vertices,
                                 uint32_t max_faces, jd_mesh_arrays *out, char *err, size_t errlen)
{
    return guarded(err, errlen, [&] {
        return read_arrays(data, size, JD_FORMAT_DRACO, ids, max_vertices, max_faces, out, err, errlen);
    });
}

extern "C" int jd_draco_encode(const jd_mesh_arrays *m, jd_draco_write_fn write, void *user, char *err, size_t errlen)
{
    return guarded(err, errlen, [&] { return encode(m, write, user, err, errlen); });
}
