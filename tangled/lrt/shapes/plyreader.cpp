// lrt/shapes/plyreader.cpp: tangled from chapters/03-shapes.md. Edit the chapter, not this file.
#include "lrt/shapes/plyreader.h"
#include "lrt/shapes/triangle.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace lrt {

namespace {

// PLY Reader Declarations
enum class PlyType {
    Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64
};

struct PlyProperty {
    std::string name;
    PlyType type;  // of the value, or of a list's items
    bool isList = false;
    PlyType countType = PlyType::UInt8;  // of a list's count
};

struct PlyElement {
    std::string name;
    int64_t count = 0;
    std::vector<PlyProperty> properties;
};

enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };
enum PlyRole {
    NoRole = -1, RoleX, RoleY, RoleZ, RoleNX, RoleNY, RoleNZ, RoleU, RoleV,
    NumRoles
};

// PLY Reader Utility Functions
bool ParsePlyType(const std::string &name, PlyType *type) {
    static const struct {
        const char *name;
        PlyType type;
    } names[] = {{"char", PlyType::Int8},      {"int8", PlyType::Int8},
                 {"uchar", PlyType::UInt8},    {"uint8", PlyType::UInt8},
                 {"short", PlyType::Int16},    {"int16", PlyType::Int16},
                 {"ushort", PlyType::UInt16},  {"uint16", PlyType::UInt16},
                 {"int", PlyType::Int32},      {"int32", PlyType::Int32},
                 {"uint", PlyType::UInt32},    {"uint32", PlyType::UInt32},
                 {"float", PlyType::Float32},  {"float32", PlyType::Float32},
                 {"double", PlyType::Float64}, {"float64", PlyType::Float64}};
    for (const auto &n : names)
        if (name == n.name) {
            *type = n.type;
            return true;
        }
    return false;
}

size_t PlyTypeSize(PlyType type) {
    switch (type) {
    case PlyType::Int8: case PlyType::UInt8: return 1;
    case PlyType::Int16: case PlyType::UInt16: return 2;
    case PlyType::Int32: case PlyType::UInt32: case PlyType::Float32:
        return 4;
    case PlyType::Float64: return 8;
    }
    return 0;
}

bool IsIntegerType(PlyType type) {
    return type != PlyType::Float32 && type != PlyType::Float64;
}
bool HostIsLittleEndian() {
    const uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

template <typename T>
double Decode(const unsigned char *bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return double(value);
}
bool FitsType(double value, PlyType type) {
    switch (type) {
    case PlyType::Int8: return value >= -128 && value <= 127;
    case PlyType::UInt8: return value >= 0 && value <= 255;
    case PlyType::Int16: return value >= -32768 && value <= 32767;
    case PlyType::UInt16: return value >= 0 && value <= 65535;
    case PlyType::Int32:
        return value >= -2147483648.0 && value <= 2147483647.0;
    case PlyType::UInt32: return value >= 0 && value <= 4294967295.0;
    default: return true;
    }
}

// PlyParser Declarations
class PlyParser {
  public:
    PlyParser(const std::string &filename, std::string data)
        : filename(filename), data(std::move(data)) {}
    PlyMesh Parse();

  private:
    // PlyParser Private Methods
    [[noreturn]] void Fail(const std::string &message,
                           bool locate = true) const {
        std::string where = "ReadPly: \"" + filename + "\": ";
        if (!locate)
            ;  // a problem of the file as a whole
        else if (inHeader || format == PlyFormat::Ascii)
            where += "line " + std::to_string(line) + ": ";
        else
            where += "byte " + std::to_string(pos) + ": ";
        if (!inHeader && element)
            where += element->name + " " + std::to_string(instance) + ": ";
        throw std::runtime_error(where + message);
    }
    std::string NextLine() {
        if (pos >= data.size())
            Fail("unexpected end of file in the header (no end_header line)");
        size_t end = data.find('\n', pos);
        if (end == std::string::npos) end = data.size();
        std::string text = data.substr(pos, end - pos);
        pos = std::min(end + 1, data.size());
        ++line;
        if (!text.empty() && text.back() == '\r') text.pop_back();
        return text;
    }

    static std::vector<std::string> Split(const std::string &text) {
        std::istringstream in(text);
        std::vector<std::string> words;
        std::string word;
        while (in >> word) words.push_back(word);
        return words;
    }
    void ParseHeader() {
        if (data.empty()) Fail("the file is empty", false);
        if (NextLine() != "ply") Fail("not a PLY file (no \"ply\" line)");
        bool haveFormat = false;
        for (;;) {
            std::vector<std::string> words = Split(NextLine());
            if (words.empty() || words[0] == "comment" ||
                words[0] == "obj_info")
                continue;
            if (words[0] == "format") {
                // Parse the PLY format line
                if (haveFormat) Fail("more than one format line");
                if (words.size() != 3) Fail("malformed format line");
                if (words[1] == "ascii")
                    format = PlyFormat::Ascii;
                else if (words[1] == "binary_little_endian")
                    format = PlyFormat::BinaryLittleEndian;
                else if (words[1] == "binary_big_endian")
                    format = PlyFormat::BinaryBigEndian;
                else
                    Fail("unsupported format \"" + words[1] + "\"");
                if (words[2] != "1.0") Fail("unsupported version \"" + words[2] + "\"");
                haveFormat = true;
            } else if (!haveFormat) {
                Fail("expected a format line after \"ply\"");
            } else if (words[0] == "element") {
                // Parse a PLY element line
                if (words.size() != 3) Fail("malformed element line");
                PlyElement e;
                e.name = words[1];
                const char *begin = words[2].c_str();
                char *end = nullptr;
                errno = 0;
                long long count = std::strtoll(begin, &end, 10);
                if (end == begin || *end != '\0' || errno == ERANGE || count < 0)
                    Fail("bad count \"" + words[2] + "\" for element " + e.name);
                e.count = count;
                elements.push_back(e);
            } else if (words[0] == "property") {
                // Parse a PLY property line
                if (elements.empty()) Fail("property declared before any element");
                PlyProperty prop;
                if (words.size() == 5 && words[1] == "list") {
                    prop.isList = true;
                    if (!ParsePlyType(words[2], &prop.countType))
                        Fail("unknown type \"" + words[2] + "\"");
                    if (!IsIntegerType(prop.countType))
                        Fail("a list's count must have an integer type");
                    if (!ParsePlyType(words[3], &prop.type))
                        Fail("unknown type \"" + words[3] + "\"");
                    prop.name = words[4];
                } else if (words.size() == 3 && words[1] != "list") {
                    if (!ParsePlyType(words[1], &prop.type))
                        Fail("unknown type \"" + words[1] + "\"");
                    prop.name = words[2];
                } else {
                    Fail("malformed property line");
                }
                elements.back().properties.push_back(prop);
            } else if (words[0] == "end_header") {
                break;
            } else {
                Fail("unknown keyword \"" + words[0] + "\" in the header");
            }
        }
    }
    int FindElement(const std::string &name) const {
        for (size_t i = 0; i < elements.size(); ++i)
            if (elements[i].name == name) return int(i);
        return -1;
    }

    static int FindProperty(const PlyElement &e, const std::string &name) {
        for (size_t i = 0; i < e.properties.size(); ++i)
            if (e.properties[i].name == name) return int(i);
        return -1;
    }
    double ReadValue(PlyType type) {
        return format == PlyFormat::Ascii ? ReadAsciiValue(type)
                                          : ReadBinaryValue(type);
    }
    double ReadBinaryValue(PlyType type) {
        size_t size = PlyTypeSize(type);
        if (data.size() - pos < size) Fail("unexpected end of file");
        unsigned char bytes[8];
        std::memcpy(bytes, data.data() + pos, size);
        pos += size;
        bool fileIsLittle = format == PlyFormat::BinaryLittleEndian;
        if (fileIsLittle != HostIsLittleEndian())
            std::reverse(bytes, bytes + size);
        switch (type) {
        case PlyType::Int8: return Decode<int8_t>(bytes);
        case PlyType::UInt8: return Decode<uint8_t>(bytes);
        case PlyType::Int16: return Decode<int16_t>(bytes);
        case PlyType::UInt16: return Decode<uint16_t>(bytes);
        case PlyType::Int32: return Decode<int32_t>(bytes);
        case PlyType::UInt32: return Decode<uint32_t>(bytes);
        case PlyType::Float32: return Decode<float>(bytes);
        case PlyType::Float64: return Decode<double>(bytes);
        }
        return 0;
    }
    std::string NextWord() {
        while (pos < data.size() &&
               (data[pos] == ' ' || data[pos] == '\t' || data[pos] == '\r'))
            ++pos;
        size_t begin = pos;
        while (pos < data.size() && !std::isspace((unsigned char)data[pos]))
            ++pos;
        return data.substr(begin, pos - begin);
    }
    double ReadAsciiValue(PlyType type) {
        std::string word = NextWord();
        if (word.empty()) Fail("too few values on the line");
        const char *begin = word.c_str();
        char *end = nullptr;
        errno = 0;
        if (IsIntegerType(type)) {
            long long value = std::strtoll(begin, &end, 10);
            if (end == begin || *end != '\0' || errno == ERANGE ||
                !FitsType(double(value), type))
                Fail("\"" + word + "\" is not a valid value of its integer "
                     "type");
            return double(value);
        }
        double value = std::strtod(begin, &end);
        if (end == begin || *end != '\0')
            Fail("\"" + word + "\" is not a number");
        return type == PlyType::Float32 ? double(float(value)) : value;
    }
    void BeginInstance() {
        if (format != PlyFormat::Ascii) return;
        for (;;) {
            ++line;
            if (pos >= data.size()) Fail("unexpected end of file");
            size_t end = data.find('\n', pos);
            if (end == std::string::npos) end = data.size();
            if (data.find_first_not_of(" \t\r", pos) < end) return;
            pos = std::min(end + 1, data.size());
        }
    }

    void EndInstance() {
        if (format != PlyFormat::Ascii) return;
        if (!NextWord().empty()) Fail("too many values on the line");
        if (pos < data.size()) ++pos;  // the newline
    }
    // PlyParser Private Data
    std::string filename, data;
    size_t pos = 0;
    int line = 0;
    bool inHeader = true;
    PlyFormat format = PlyFormat::Ascii;
    std::vector<PlyElement> elements;
    const PlyElement *element = nullptr;
    int64_t instance = 0;
};

// PlyParser Method Definitions
PlyMesh PlyParser::Parse() {
    ParseHeader();
    inHeader = false;
    PlyMesh mesh;
    // Find the vertex and face elements and the properties lrt uses
    int vertexElement = FindElement("vertex"), faceElement = FindElement("face");
    if (vertexElement < 0) Fail("the file has no vertex element", false);
    if (faceElement < 0) Fail("the file has no face element", false);
    const PlyElement &vertices = elements[vertexElement];
    const PlyElement &faces = elements[faceElement];
    if (vertices.count > std::numeric_limits<int>::max() ||
        faces.count > std::numeric_limits<int>::max())
        Fail("too many vertices or faces for lrt's int indices", false);
    std::vector<int> roles(vertices.properties.size(), NoRole);
    // Assign roles to the vertex properties
    auto assign = [&](const char *name, int role) {
        int i = FindProperty(vertices, name);
        if (i < 0) return false;
        if (vertices.properties[i].isList)
            Fail(std::string("vertex property ") + name + " is a list", false);
        roles[i] = role;
        return true;
    };
    bool hasXYZ[3] = {assign("x", RoleX), assign("y", RoleY),
                      assign("z", RoleZ)};
    if (!hasXYZ[0] || !hasXYZ[1] || !hasXYZ[2])
        Fail("the vertex element lacks x, y or z", false);
    int nNormal = assign("nx", RoleNX) + assign("ny", RoleNY) +
                  assign("nz", RoleNZ);
    if (nNormal != 0 && nNormal != 3)
        Fail("the vertex element has some but not all of nx, ny, nz",
             false);
    bool hasNormals = nNormal == 3;
    const char *uvNames[4][2] = {{"u", "v"}, {"s", "t"},
                                 {"texture_u", "texture_v"},
                                 {"texture_s", "texture_t"}};
    bool hasUV = false;
    for (int i = 0; i < 4 && !hasUV; ++i)
        if (FindProperty(vertices, uvNames[i][0]) >= 0 &&
            FindProperty(vertices, uvNames[i][1]) >= 0)
            hasUV = assign(uvNames[i][0], RoleU) &&
                    assign(uvNames[i][1], RoleV);
    // Find the face property with the vertex indices
    int indexProperty = FindProperty(faces, "vertex_indices");
    if (indexProperty < 0) indexProperty = FindProperty(faces, "vertex_index");
    if (indexProperty < 0)
        Fail("the face element has no vertex_indices property", false);
    const PlyProperty &indexProp = faces.properties[indexProperty];
    if (!indexProp.isList || !IsIntegerType(indexProp.type))
        Fail("vertex_indices must be a list of integers", false);
    for (const PlyElement &e : elements) {
        element = &e;
        // Read all instances of element e
        bool isVertex = &e == &vertices, isFace = &e == &faces;
        int64_t bound = std::min<int64_t>(e.count, int64_t(data.size() - pos));
        if (isVertex) {
            mesh.p.reserve(bound);
            if (hasNormals) mesh.n.reserve(bound);
            if (hasUV) mesh.uv.reserve(bound);
        }
        if (isFace) mesh.vertexIndices.reserve(3 * bound);
        std::vector<int64_t> polygon;
        for (instance = 0; instance < e.count; ++instance) {
            double value[NumRoles] = {};
            polygon.clear();
            BeginInstance();
            for (size_t i = 0; i < e.properties.size(); ++i) {
                const PlyProperty &prop = e.properties[i];
                if (prop.isList) {
                    // Read a PLY list property
                    double count = ReadValue(prop.countType);
                    if (count < 0) Fail("negative list length");
                    bool isIndexList = isFace && int(i) == indexProperty;
                    for (int64_t k = 0; k < int64_t(count); ++k) {
                        double x = ReadValue(prop.type);
                        if (isIndexList) polygon.push_back(int64_t(x));
                    }
                } else {
                    double x = ReadValue(prop.type);
                    if (isVertex && roles[i] != NoRole) value[roles[i]] = x;
                }
            }
            EndInstance();
            if (isVertex) {
                // Store the vertex in mesh
                Point3f p = Point3f(Float(value[RoleX]), Float(value[RoleY]),
                                    Float(value[RoleZ]));
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    Fail("vertex position is not finite");
                mesh.p.push_back(p);
                if (hasNormals)
                    mesh.n.push_back(Normal3f(Float(value[RoleNX]), Float(value[RoleNY]),
                                              Float(value[RoleNZ])));
                if (hasUV)
                    mesh.uv.push_back(Point2f(Float(value[RoleU]), Float(value[RoleV])));
            }
            if (isFace) {
                // Triangulate the polygon and store its triangles in mesh
                if (polygon.size() < 3)
                    Fail("a face needs at least 3 vertices, this one has " +
                         std::to_string(polygon.size()));
                for (int64_t index : polygon)
                    if (index < 0 || index >= vertices.count)
                        Fail("vertex index " + std::to_string(index) +
                             " is out of range; the file has " +
                             std::to_string(vertices.count) + " vertices");
                for (size_t k = 1; k + 1 < polygon.size(); ++k) {
                    mesh.vertexIndices.push_back(int(polygon[0]));
                    mesh.vertexIndices.push_back(int(polygon[k]));
                    mesh.vertexIndices.push_back(int(polygon[k + 1]));
                }
            }
        }
    }
    element = nullptr;
    // Check that no data follows the last element
    if (format == PlyFormat::Ascii) {
        size_t next = data.find_first_not_of(" \t\r\n", pos);
        if (next != std::string::npos) {
            line += int(std::count(data.begin() + pos, data.begin() + next,
                                   '\n')) + 1;
            Fail("unexpected data after the last element");
        }
    } else if (pos != data.size()) {
        Fail(std::to_string(data.size() - pos) +
             " bytes of unexpected data after the last element");
    }
    return mesh;
}

}  // namespace

// PLY Function Definitions
PlyMesh ReadPly(const std::string &filename) {
    std::FILE *f = std::fopen(filename.c_str(), "rb");
    if (!f)
        throw std::runtime_error("ReadPly: cannot open \"" + filename +
                                 "\": " + std::strerror(errno));
    std::string data;
    char buffer[65536];
    size_t n;
    while ((n = std::fread(buffer, 1, sizeof(buffer), f)) > 0)
        data.append(buffer, n);
    int error = std::ferror(f) ? errno : 0;
    std::fclose(f);
    if (error)
        throw std::runtime_error("ReadPly: cannot read \"" + filename +
                                 "\": " + std::strerror(error));
    return PlyParser(filename, std::move(data)).Parse();
}
std::vector<std::shared_ptr<Shape>> CreatePLYMesh(
    const Transform *ObjectToWorld, const Transform *WorldToObject,
    bool reverseOrientation, const std::string &filename) {
    PlyMesh m = ReadPly(filename);
    return CreateTriangleMesh(
        ObjectToWorld, WorldToObject, reverseOrientation, m.nTriangles(),
        m.vertexIndices.data(), m.nVertices(), m.p.data(), nullptr,
        m.n.empty() ? nullptr : m.n.data(),
        m.uv.empty() ? nullptr : m.uv.data());
}

}  // namespace lrt
