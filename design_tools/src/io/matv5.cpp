// matv5.cpp - MATLAB level-5 MAT-file reader (see matv5.hpp for the layout).
#include "fracdesign/io/matv5.hpp"

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

namespace fracdesign {
namespace io {
namespace {

// Data types of tagged elements (MAT-File Format, Table 1-1).
enum MiType : std::uint32_t {
    miINT8 = 1, miUINT8 = 2, miINT16 = 3, miUINT16 = 4, miINT32 = 5, miUINT32 = 6,
    miSINGLE = 7, miDOUBLE = 9, miINT64 = 12, miUINT64 = 13, miMATRIX = 14, miCOMPRESSED = 15
};

const char* class_name(unsigned c)
{
    static const char* names[] = {"?", "cell", "struct", "object", "char", "sparse", "double", "single",
                                  "int8", "uint8", "int16", "uint16", "int32", "uint32", "int64", "uint64"};
    return c < 16 ? names[c] : "?";
}

std::size_t type_size(std::uint32_t t)
{
    switch (t) {
    case miINT8: case miUINT8: return 1;
    case miINT16: case miUINT16: return 2;
    case miINT32: case miUINT32: case miSINGLE: return 4;
    case miDOUBLE: case miINT64: case miUINT64: return 8;
    default: return 0;
    }
}

template <class T>
T load(const unsigned char* p)
{
    T v;
    std::memcpy(&v, p, sizeof v);  // the file is little-endian, as is every supported host
    return v;
}

double element_value(std::uint32_t t, const unsigned char* p)
{
    switch (t) {
    case miINT8: return load<std::int8_t>(p);
    case miUINT8: return load<std::uint8_t>(p);
    case miINT16: return load<std::int16_t>(p);
    case miUINT16: return load<std::uint16_t>(p);
    case miINT32: return load<std::int32_t>(p);
    case miUINT32: return load<std::uint32_t>(p);
    case miSINGLE: return load<float>(p);
    case miDOUBLE: return load<double>(p);
    case miINT64: return double(load<std::int64_t>(p));
    default: return double(load<std::uint64_t>(p));
    }
}

// One tagged element inside [p, end): its type, payload and the offset of the
// next element. `padded` is false only for miCOMPRESSED at top level, whose
// payload MATLAB does not pad to 8 bytes.
struct Element {
    std::uint32_t type = 0;
    const unsigned char* data = nullptr;
    std::size_t size = 0;
    std::size_t next = 0;
};

Element read_element(const unsigned char* base, std::size_t off, std::size_t end, const std::string& where)
{
    if (off + 8 > end) throw MatError(where + ": truncated element tag");
    Element e;
    const std::uint32_t w0 = load<std::uint32_t>(base + off);
    if (w0 >> 16) {  // small data element: type and size share the first word
        e.type = w0 & 0xffffu;
        e.size = w0 >> 16;
        if (e.size > 4) throw MatError(where + ": corrupt small data element");
        e.data = base + off + 4;
        e.next = off + 8;
        return e;
    }
    e.type = w0;
    e.size = load<std::uint32_t>(base + off + 4);
    if (e.size > end - off - 8) throw MatError(where + ": truncated element (needs " + std::to_string(e.size) + " bytes)");
    e.data = base + off + 8;
    const std::size_t padded = e.type == miCOMPRESSED ? e.size : (e.size + 7) / 8 * 8;
    e.next = off + 8 + padded;
    if (e.next > end) e.next = end;  // the last element may lack its padding
    return e;
}

std::vector<unsigned char> inflate_all(const unsigned char* p, std::size_t n, const std::string& where)
{
    std::vector<unsigned char> out;
    z_stream zs;
    std::memset(&zs, 0, sizeof zs);
    if (inflateInit(&zs) != Z_OK) throw MatError(where + ": zlib init failed");
    zs.next_in = const_cast<unsigned char*>(p);
    zs.avail_in = static_cast<uInt>(n);
    unsigned char buf[65536];
    int rc;
    do {
        zs.next_out = buf;
        zs.avail_out = sizeof buf;
        rc = inflate(&zs, Z_NO_FLUSH);
        if (rc != Z_OK && rc != Z_STREAM_END) {
            inflateEnd(&zs);
            throw MatError(where + ": corrupt compressed data (zlib error " + std::to_string(rc) + ")");
        }
        out.insert(out.end(), buf, buf + (sizeof buf - zs.avail_out));
    } while (rc != Z_STREAM_END && (zs.avail_in > 0 || zs.avail_out == 0));
    inflateEnd(&zs);
    if (rc != Z_STREAM_END) throw MatError(where + ": truncated compressed data");
    return out;
}

void parse_matrix(const Element& m, MatFile& file, const std::string& origin)
{
    const unsigned char* b = m.data;
    const std::size_t end = m.size;
    const std::string w = origin + ": miMATRIX";
    const Element flags = read_element(b, 0, end, w);
    if (flags.type != miUINT32 || flags.size != 8) throw MatError(w + ": bad array flags");
    const std::uint32_t fw = load<std::uint32_t>(flags.data);
    const unsigned cls = fw & 0xffu;
    const bool complex = (fw >> 11) & 1u;
    const Element dims = read_element(b, flags.next, end, w);
    if (dims.type != miINT32 || dims.size % 4) throw MatError(w + ": bad dimensions");
    std::vector<std::int32_t> d(dims.size / 4);
    for (std::size_t i = 0; i < d.size(); ++i) d[i] = load<std::int32_t>(dims.data + 4 * i);
    const Element nm = read_element(b, dims.next, end, w);
    if (nm.type != miINT8) throw MatError(w + ": bad array name");
    const std::string name(reinterpret_cast<const char*>(nm.data), nm.size);
    const std::string wv = origin + ": variable '" + name + "'";
    if (cls < 6 || cls > 15 || complex || d.size() != 2) {
        file.skipped.push_back(name + " (" + class_name(cls) + (complex ? ", complex" : "") +
                               (d.size() != 2 ? ", " + std::to_string(d.size()) + "-D" : "") + ")");
        return;
    }
    if (d[0] < 0 || d[1] < 0) throw MatError(wv + ": negative dimension");
    MatMatrix mm;
    mm.rows = std::size_t(d[0]);
    mm.cols = std::size_t(d[1]);
    mm.mclass = class_name(cls);
    const std::size_t count = mm.rows * mm.cols;
    const Element re = read_element(b, nm.next, end, wv);
    const std::size_t es = type_size(re.type);
    if (es == 0) throw MatError(wv + ": unsupported storage type " + std::to_string(re.type));
    if (re.size != count * es)
        throw MatError(wv + ": " + std::to_string(re.size) + " data bytes for " + std::to_string(mm.rows) + "x" +
                       std::to_string(mm.cols) + " elements of " + std::to_string(es) + " bytes");
    mm.data.resize(count);
    for (std::size_t i = 0; i < count; ++i) mm.data[i] = element_value(re.type, re.data + i * es);
    file.vars[name] = std::move(mm);
}

}  // namespace

double MatMatrix::scalar() const
{
    if (rows != 1 || cols != 1)
        throw MatError("expected a scalar, got " + std::to_string(rows) + "x" + std::to_string(cols));
    return data[0];
}

const MatMatrix& MatFile::at(const std::string& name) const
{
    const auto it = vars.find(name);
    if (it != vars.end()) return it->second;
    std::string have;
    for (const auto& kv : vars) have += (have.empty() ? "" : ", ") + kv.first;
    throw MatError(origin + ": no numeric variable '" + name + "' (has: " + have + ")");
}

std::vector<double> MatFile::vector(const std::string& name) const
{
    const MatMatrix& m = at(name);
    if (m.rows != 1 && m.cols != 1)
        throw MatError(origin + ": variable '" + name + "' is " + std::to_string(m.rows) + "x" +
                       std::to_string(m.cols) + ", expected a vector");
    return m.data;
}

MatFile parse_mat_v5(const std::vector<unsigned char>& bytes, const std::string& origin)
{
    if (bytes.size() < 128) throw MatError(origin + ": too short for a MAT-file header");
    if (bytes[126] == 'M' && bytes[127] == 'I')
        throw MatError(origin + ": big-endian MAT-file not supported");
    if (bytes[126] != 'I' || bytes[127] != 'M' || load<std::uint16_t>(&bytes[124]) != 0x0100)
        throw MatError(origin + ": not a MATLAB level-5 MAT-file (v7.3/HDF5 and v4 are not supported)");
    MatFile f;
    f.origin = origin;
    f.header.assign(reinterpret_cast<const char*>(bytes.data()), 116);
    f.header.erase(f.header.find_last_not_of(" \0", std::string::npos, 2) + 1);
    std::size_t off = 128;
    while (off < bytes.size()) {
        const Element e = read_element(bytes.data(), off, bytes.size(), origin);
        if (e.type == miCOMPRESSED) {
            const std::vector<unsigned char> raw = inflate_all(e.data, e.size, origin);
            const Element inner = read_element(raw.data(), 0, raw.size(), origin);
            if (inner.type == miMATRIX) parse_matrix(inner, f, origin);
        } else if (e.type == miMATRIX) {
            parse_matrix(e, f, origin);
        }
        off = e.next;
    }
    return f;
}

MatFile read_mat_v5(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MatError(path + ": cannot open");
    std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parse_mat_v5(bytes, path);
}

}  // namespace io
}  // namespace fracdesign
