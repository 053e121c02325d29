// Tests of the PLY reader (Chapter 3, "Reading Meshes"). The tests write
// their own files, in ASCII and in binary of both byte orders, with an
// independent writer, read them back and compare; and they check that every
// kind of malformed file is rejected with a message that says what is wrong
// and where.
//
// Every test that parses a file belongs to exercise ex-3.24 (suites
// Ex3_24_*), whose fragments parse the header lines of every file; those
// tests hand the files' bytes to the exercise calls of exercise_calls.h,
// which write and read them.

#include "lrt/shapes/plyreader.h"
#include "lrt/shapes/triangle.h"

#include "exercise_calls.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

using namespace lrt;

namespace {

enum class Fmt { Ascii, Little, Big };

const char *FormatName(Fmt f) {
    return f == Fmt::Ascii    ? "ascii"
           : f == Fmt::Little ? "binary_little_endian"
                              : "binary_big_endian";
}

// Builds the bytes of a PLY file: header lines, then values of given PLY
// types, written as text or as bytes in the requested order.
class PlyBuilder {
  public:
    explicit PlyBuilder(Fmt f, bool writeFormat = true) : fmt(f) {
        Line("ply");
        if (writeFormat) Line(std::string("format ") + FormatName(f) + " 1.0");
    }
    void Line(const std::string &l) { header += l + "\n"; }
    void Put(const std::string &type, double v) {
        if (fmt == Fmt::Ascii) {
            char buf[64];
            if (type == "float" || type == "float32")
                std::snprintf(buf, sizeof(buf), "%.9g ", v);
            else if (type == "double" || type == "float64")
                std::snprintf(buf, sizeof(buf), "%.17g ", v);
            else
                std::snprintf(buf, sizeof(buf), "%lld ", (long long)v);
            body += buf;
            return;
        }
        if (type == "char" || type == "int8") Bytes<int8_t>(int8_t(v));
        else if (type == "uchar" || type == "uint8") Bytes<uint8_t>(uint8_t(v));
        else if (type == "short" || type == "int16") Bytes<int16_t>(int16_t(v));
        else if (type == "ushort" || type == "uint16")
            Bytes<uint16_t>(uint16_t(v));
        else if (type == "int" || type == "int32") Bytes<int32_t>(int32_t(v));
        else if (type == "uint" || type == "uint32")
            Bytes<uint32_t>(uint32_t(v));
        else if (type == "float" || type == "float32") Bytes<float>(float(v));
        else if (type == "double" || type == "float64") Bytes<double>(v);
        else ADD_FAILURE() << "test writer: unknown type " << type;
    }
    void Raw(const std::string &text) { body += text; }
    void EndInstance() {
        if (fmt == Fmt::Ascii) {
            if (!body.empty() && body.back() == ' ') body.pop_back();
            body += "\n";
        }
    }
    std::string Contents() const { return header + body; }
    Fmt fmt;
    std::string header, body;

  private:
    template <typename T>
    void Bytes(T v) {
        unsigned char b[sizeof(T)];
        std::memcpy(b, &v, sizeof(T));
        uint16_t one = 1;
        bool hostLittle = *reinterpret_cast<unsigned char *>(&one) == 1;
        bool wantLittle = fmt == Fmt::Little;
        for (size_t i = 0; i < sizeof(T); ++i)
            body += char(b[hostLittle == wantLittle ? i : sizeof(T) - 1 - i]);
    }
};


struct TestMesh {
    std::vector<Point3f> p;
    std::vector<Normal3f> n;
    std::vector<Point2f> uv;
    std::vector<std::vector<int>> faces;
};

TestMesh RandomMesh(std::mt19937_64 &rng, int nv, int nf) {
    std::uniform_real_distribution<float> u(-100, 100);
    TestMesh m;
    for (int i = 0; i < nv; ++i) {
        m.p.push_back(Point3f(u(rng), u(rng), u(rng)));
        m.n.push_back(Normal3f(u(rng), u(rng), u(rng)));
        m.uv.push_back(Point2f(u(rng), u(rng)));
    }
    std::uniform_int_distribution<int> vi(0, nv - 1), size(3, 6);
    for (int i = 0; i < nf; ++i) {
        std::vector<int> f(size(rng));
        for (int &k : f) k = vi(rng);
        m.faces.push_back(f);
    }
    return m;
}

// Writes m with the given property types and names; optionally with extra
// properties and elements that the reader must skip.
std::string WriteMesh(const TestMesh &m, Fmt fmt, const std::string &coord,
                      const std::string &countType,
                      const std::string &indexType, bool extras,
                      const char *uName = "u", const char *vName = "v",
                      const char *listName = "vertex_indices") {
    PlyBuilder b(fmt);
    b.Line("comment written by test_ply.cpp");
    if (extras) {
        b.Line("element material 2");
        b.Line("property list uchar float tint");
        b.Line("property short id");
    }
    b.Line("element vertex " + std::to_string(m.p.size()));
    b.Line("property " + coord + " x");
    if (extras) b.Line("property uchar red");
    b.Line("property " + coord + " y");
    b.Line("property " + coord + " z");
    b.Line("property float nx");
    b.Line("property float ny");
    b.Line("property float nz");
    if (extras) b.Line("property list ushort int8 junk");
    b.Line(std::string("property float ") + uName);
    b.Line(std::string("property float ") + vName);
    b.Line("element face " + std::to_string(m.faces.size()));
    if (extras) b.Line("property double quality");
    b.Line("property list " + countType + " " + indexType + " " + listName);
    if (extras) {
        b.Line("element edge 1");
        b.Line("property int vertex1");
        b.Line("property uint vertex2");
    }
    b.Line("end_header");
    if (extras) {
        b.Put("uchar", 2);
        b.Put("float", 0.5);
        b.Put("float", -1.25);
        b.Put("short", -7);
        b.EndInstance();
        b.Put("uchar", 0);
        b.Put("short", 300);
        b.EndInstance();
    }
    for (size_t i = 0; i < m.p.size(); ++i) {
        b.Put(coord, m.p[i].x);
        if (extras) b.Put("uchar", 200);
        b.Put(coord, m.p[i].y);
        b.Put(coord, m.p[i].z);
        b.Put("float", m.n[i].x);
        b.Put("float", m.n[i].y);
        b.Put("float", m.n[i].z);
        if (extras) {
            b.Put("ushort", i % 3);
            for (size_t k = 0; k < i % 3; ++k) b.Put("int8", -3);
        }
        b.Put("float", m.uv[i].x);
        b.Put("float", m.uv[i].y);
        b.EndInstance();
    }
    for (const auto &f : m.faces) {
        if (extras) b.Put("double", 0.125);
        b.Put(countType, double(f.size()));
        for (int k : f) b.Put(indexType, k);
        b.EndInstance();
    }
    if (extras) {
        b.Put("int", 1);
        b.Put("uint", 2);
        b.EndInstance();
    }
    return b.Contents();
}

void ExpectSameMesh(const TestMesh &m, const PlyMesh &r, bool exactFloat) {
    ASSERT_EQ(r.nVertices(), int(m.p.size()));
    ASSERT_EQ(r.n.size(), m.n.size());
    ASSERT_EQ(r.uv.size(), m.uv.size());
    for (size_t i = 0; i < m.p.size(); ++i) {
        // float values survive every format exactly; so do doubles when
        // Float is double.
        if (exactFloat) {
            EXPECT_EQ(r.p[i], m.p[i]) << "vertex " << i;
        } else {
            for (int k = 0; k < 3; ++k)
                EXPECT_FLOAT_EQ(float(r.p[i][k]), float(m.p[i][k]));
        }
        EXPECT_EQ(r.n[i], m.n[i]) << "normal " << i;
        EXPECT_EQ(r.uv[i], m.uv[i]) << "uv " << i;
    }
    std::vector<int> want;
    for (const auto &f : m.faces)
        for (size_t k = 1; k + 1 < f.size(); ++k) {
            want.push_back(f[0]);
            want.push_back(f[k]);
            want.push_back(f[k + 1]);
        }
    EXPECT_EQ(r.vertexIndices, want);
}

}  // namespace

// Round trips: a random mesh of triangles, quads, pentagons and hexagons,
// with normals and uv, in all three formats, with various property types,
// names, and extra elements and properties that must be skipped.
EXERCISE_TEST(Ex3_24_PlyReader, RoundTripAllFormats) {
    std::mt19937_64 rng(calls::Seed(5));
    TestMesh m = RandomMesh(rng, 300, 500);
    struct Variant {
        std::string coord, countType, indexType;
        bool extras;
        const char *u, *v, *list;
    };
    std::vector<Variant> variants = {
        {"float", "uchar", "int", false, "u", "v", "vertex_indices"},
        {"float32", "uint8", "int32", true, "s", "t", "vertex_index"},
        {"double", "int", "uint", true, "texture_u", "texture_v",
         "vertex_indices"},
        {"float", "ushort", "ushort", true, "texture_s", "texture_t",
         "vertex_indices"}};
    int files = 0;
    for (Fmt fmt : {Fmt::Ascii, Fmt::Little, Fmt::Big})
        for (const Variant &v : variants) {
            std::string name = std::string("roundtrip_") + FormatName(fmt) +
                               "_" + std::to_string(files) + ".ply";
            PlyMesh r = ex::ReadPly(name, WriteMesh(m, fmt, v.coord,
                                                    v.countType, v.indexType,
                                                    v.extras, v.u, v.v,
                                                    v.list));
            ExpectSameMesh(m, r, true);
            ++files;
        }
    std::printf("[ ply      ] %d files round-tripped (%zu vertices, %zu "
                "polygons each)\n", files, m.p.size(), m.faces.size());
}

EXERCISE_TEST(Ex3_24_PlyReader, AsciiLayoutAndComments) {
    // CRLF line ends, comments and obj_info in the header, blank lines and
    // tabs in the data, a last line without a newline.
    std::string text =
        "ply\r\n"
        "comment first\r\n"
        "format ascii 1.0\r\n"
        "obj_info made by hand\r\n"
        "element vertex 4\r\n"
        "property float x\r\nproperty float y\r\nproperty float z\r\n"
        "element face 1\r\n"
        "property list uchar int vertex_indices\r\n"
        "end_header\r\n"
        "0 0 0\r\n"
        "\r\n"
        "1\t0 0\r\n"
        "  1 1 0  \r\n"
        "0 1 0\r\n"
        "4 0 1 2 3";
    PlyMesh r = ex::ReadPly("layout.ply", text);
    ASSERT_EQ(r.nVertices(), 4);
    EXPECT_EQ(r.p[2], Point3f(1, 1, 0));
    EXPECT_TRUE(r.n.empty());
    EXPECT_TRUE(r.uv.empty());
    EXPECT_EQ(r.vertexIndices, (std::vector<int>{0, 1, 2, 0, 2, 3}));
}

// A cube written as six quads (binary, big-endian) becomes twelve triangles
// that a transformed ray hits where it should.
EXERCISE_TEST(Ex3_24_PlyReader, CreatePLYMeshMakesTriangles) {
    PlyBuilder b(Fmt::Big);
    b.Line("element vertex 8");
    b.Line("property float x");
    b.Line("property float y");
    b.Line("property float z");
    b.Line("element face 6");
    b.Line("property list uchar uint vertex_indices");
    b.Line("end_header");
    for (int i = 0; i < 8; ++i) {
        b.Put("float", (i & 1) ? 1 : -1);
        b.Put("float", (i & 2) ? 1 : -1);
        b.Put("float", (i & 4) ? 1 : -1);
    }
    int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                       {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto &q : quads) {
        b.Put("uchar", 4);
        for (int k : q) b.Put("uint", k);
    }
    const Transform o2w = Translate(Vector3f(0, 0, 10)) * Scale(2, 2, 2);
    Ray ray(Point3f(Float(0.3), Float(-0.2), 0), Vector3f(0, 0, 1));
    PlyShapes tris =
        ex::CreatePLYMeshFile("cube.ply", b.Contents(), o2w, false, ray);
    ASSERT_EQ(tris.worldBounds.size(), 12u);
    ASSERT_GE(tris.nearest.triangle, 0);
    EXPECT_FLOAT_EQ(float(tris.nearest.tHit), 8);
    // The quads are wound so that their normals point out of the cube.
    EXPECT_FLOAT_EQ(float(tris.nearest.isect.n.z), -1);
    // Every triangle of the cube is front-facing from outside along some
    // axis, and the bound of the mesh is the transformed cube.
    Bounds3f all = tris.worldBounds[0];
    for (const Bounds3f &b : tris.worldBounds) all = Union(all, b);
    EXPECT_EQ(all.pMin, Point3f(-2, -2, 8));
    EXPECT_EQ(all.pMax, Point3f(2, 2, 12));
}

// ---------------------------------------------------------------------------
// Malformed files. Each case is a file and the pieces its error message must
// contain; every message starts with the function's name and the file's.

namespace {

const char *kGoodHeader =
    "element vertex 3\nproperty float x\nproperty float y\n"
    "property float z\nelement face 1\n"
    "property list uchar int vertex_indices\nend_header\n";

std::string Ascii(const std::string &headerAndData) {
    return "ply\nformat ascii 1.0\n" + headerAndData;
}

// A valid binary triangle file, little-endian.
std::string BinaryTriangle(int index2 = 2) {
    PlyBuilder b(Fmt::Little);
    b.header += kGoodHeader;
    for (int i = 0; i < 9; ++i) b.Put("float", i);
    b.Put("uchar", 3);
    b.Put("int", 0);
    b.Put("int", 1);
    b.Put("int", index2);
    return b.Contents();
}

}  // namespace

EXERCISE_TEST(Ex3_24_PlyReader, ErrorMessagesNameFileAndProblem) {
    struct Case {
        const char *name;
        std::string contents;
        std::vector<std::string> expect;
    };
    std::string good = BinaryTriangle();
    std::vector<Case> cases = {
        {"empty", "", {"the file is empty"}},
        {"notply", "PLY\nformat ascii 1.0\n", {"line 1", "not a PLY file"}},
        {"middleendian", "ply\nformat binary_middle_endian 1.0\n",
         {"line 2", "unsupported format \"binary_middle_endian\""}},
        {"version", "ply\nformat ascii 2.0\n",
         {"line 2", "unsupported version \"2.0\""}},
        {"noformat", "ply\nelement vertex 3\n",
         {"line 2", "expected a format line"}},
        {"twoformats", "ply\nformat ascii 1.0\nformat ascii 1.0\n",
         {"line 3", "more than one format line"}},
        {"keyword", Ascii("element vertex 3\nproperty float x\nfoo bar\n"),
         {"line 5", "unknown keyword \"foo\""}},
        {"propfirst", Ascii("property float x\n"),
         {"line 3", "property declared before any element"}},
        {"badtype", Ascii("element vertex 3\nproperty float16 x\n"),
         {"line 4", "unknown type \"float16\""}},
        {"floatcount",
         Ascii("element face 1\nproperty list float int vertex_indices\n"),
         {"line 4", "count must have an integer type"}},
        {"badproperty", Ascii("element vertex 1\nproperty float\n"),
         {"line 4", "malformed property line"}},
        {"negcount", Ascii("element vertex -3\n"),
         {"line 3", "bad count \"-3\" for element vertex"}},
        {"garbagecount", Ascii("element vertex 12abc\n"),
         {"line 3", "bad count \"12abc\""}},
        {"noendheader", Ascii("element vertex 3\nproperty float x\n"),
         {"line 4", "unexpected end of file in the header",
          "no end_header"}},
        {"novertex",
         Ascii("element face 1\nproperty list uchar int vertex_indices\n"
               "end_header\n3 0 1 2\n"),
         {"the file has no vertex element"}},
        {"noface",
         Ascii("element vertex 1\nproperty float x\nproperty float y\n"
               "property float z\nend_header\n0 0 0\n"),
         {"the file has no face element"}},
        {"noz",
         Ascii("element vertex 1\nproperty float x\nproperty float y\n"
               "element face 0\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0\n"),
         {"the vertex element lacks x, y or z"}},
        {"partialnormal",
         Ascii("element vertex 1\nproperty float x\nproperty float y\n"
               "property float z\nproperty float nx\nelement face 0\n"
               "property list uchar int vertex_indices\nend_header\n"
               "0 0 0 1\n"),
         {"some but not all of nx, ny, nz"}},
        {"scalarindices",
         Ascii("element vertex 1\nproperty float x\nproperty float y\n"
               "property float z\nelement face 0\n"
               "property int vertex_indices\nend_header\n0 0 0\n"),
         {"vertex_indices must be a list of integers"}},
        {"floatindices",
         Ascii("element vertex 1\nproperty float x\nproperty float y\n"
               "property float z\nelement face 0\n"
               "property list uchar float vertex_indices\nend_header\n"
               "0 0 0\n"),
         {"vertex_indices must be a list of integers"}},
        {"listcoord",
         Ascii("element vertex 1\nproperty list uchar float x\n"
               "property float y\nproperty float z\nelement face 0\n"
               "property list uchar int vertex_indices\nend_header\n"
               "1 0 0 0\n"),
         {"vertex property x is a list"}},
        {"asciitruncated", Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n"),
         {"line 12", "vertex 2", "unexpected end of file"}},
        {"asciifew", Ascii(std::string(kGoodHeader) + "0 0 0\n1 0\n"),
         {"line 11", "vertex 1", "too few values on the line"}},
        {"asciimany",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0 7\n"),
         {"line 12", "vertex 2", "too many values on the line"}},
        {"asciinotnumber",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 abc 0\n"),
         {"line 11", "vertex 1", "\"abc\" is not a number"}},
        {"asciifractionalindex",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n"),
         {"line 13", "face 0", "\"2.5\" is not a valid value"}},
        {"asciicountrange",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0\n300 0 1 2\n"),
         {"line 13", "face 0", "\"300\" is not a valid value"}},
        {"asciinan", Ascii(std::string(kGoodHeader) + "0 0 0\nnan 0 0\n"),
         {"line 11", "vertex 1", "vertex position is not finite"}},
        {"asciiinf", Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 1e39\n"),
         {"line 11", "vertex 1", "vertex position is not finite"}},
        {"asciirange",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
         {"line 13", "face 0", "vertex index 7 is out of range",
          "the file has 3 vertices"}},
        {"asciinegative",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
         {"line 13", "face 0", "vertex index -1 is out of range"}},
        {"asciitwogon",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n"),
         {"line 13", "face 0", "a face needs at least 3 vertices",
          "this one has 2"}},
        {"asciitrailing",
         Ascii(std::string(kGoodHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n\n"
               "5 5\n"),
         {"line 15", "unexpected data after the last element"}},
        {"binaryrange", BinaryTriangle(3),
         {"byte 218", "face 0", "vertex index 3 is out of range",
          "the file has 3 vertices"}},
        {"binarytruncated", good.substr(0, good.size() - 3),
         {"byte 214", "face 0", "unexpected end of file"}},
        {"binaryheaderonly", good.substr(0, good.size() - 49),
         {"byte 169", "vertex 0", "unexpected end of file"}},
        {"binarytrailing", good + "xyz",
         {"byte 218", "3 bytes of unexpected data after the last element"}},
    };
    // A header that declares four billion vertices, followed by three: the
    // reader must fail at the end of the data, not try to allocate memory
    // for the declared count.
    {
        std::string huge = good;
        huge.replace(huge.find("vertex 3"), 8, "vertex 4000000000");
        cases.push_back({"hugecount", huge, {"too many vertices or faces"}});
        std::string big = good;
        big.replace(big.find("vertex 3"), 8, "vertex 2000000000");
        cases.push_back({"bigcount", big, {"vertex 4", "unexpected end"}});
    }
    // A signed list count that is negative.
    {
        PlyBuilder b(Fmt::Little);
        b.header += "element vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\n"
                    "property list char int vertex_indices\nend_header\n";
        for (int i = 0; i < 9; ++i) b.Put("float", i);
        b.Put("char", -1);
        cases.push_back({"negativelist", b.Contents(),
                         {"face 0", "negative list length"}});
    }
    for (const Case &c : cases) {
        std::string name = std::string(c.name) + ".ply";
        std::string message = ex::ReadPlyError(name, c.contents);
        ASSERT_FALSE(message.empty()) << c.name << ": no error";
        size_t prefix = ex::PlyFilePrefix(message, name);
        EXPECT_GT(prefix, 0u) << c.name << ": " << message;
        for (const std::string &e : c.expect)
            EXPECT_NE(message.find(e), std::string::npos)
                << c.name << ": \"" << message << "\" lacks \"" << e << "\"";
        // Problems of the file as a whole come without a location; all
        // others with a line or a byte offset.
        std::set<std::string> whole = {
            "empty",         "novertex",      "noface",    "noz",
            "partialnormal", "scalarindices", "floatindices", "listcoord",
            "hugecount"};
        bool located = message.compare(prefix, 5, "line ") == 0 ||
                       message.compare(prefix, 5, "byte ") == 0;
        EXPECT_EQ(located, whole.count(c.name) == 0) << message;
    }
    // The binary triangle itself is fine.
    PlyMesh ok = ex::ReadPly("goodbinary.ply", good);
    EXPECT_EQ(ok.vertexIndices, (std::vector<int>{0, 1, 2}));
    EXPECT_EQ(ok.p[2], Point3f(6, 7, 8));
    std::printf("[ ply      ] %zu malformed files rejected\n", cases.size());
}

// Files that cannot be read: the reader fails before it parses anything.

namespace {

// The message of the exception that ReadPly() throws, or "" if none.
std::string ReadError(const std::string &path) {
    try {
        ReadPly(path);
    } catch (const std::runtime_error &e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(PlyReader, MissingFile) {
    std::string path = ::testing::TempDir() + "lrt_test_does_not_exist.ply";
    std::remove(path.c_str());
    std::string message = ReadError(path);
    EXPECT_NE(message.find("ReadPly: cannot open \"" + path + "\""),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("No such file or directory"), std::string::npos)
        << message;
    const Transform id;
    EXPECT_THROW(CreatePLYMesh(&id, &id, false, path), std::runtime_error);
    // A directory is not a file.
    std::string dir = ::testing::TempDir();
    message = ReadError(dir);
    EXPECT_NE(message.find("ReadPly: cannot read \"" + dir + "\""),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("Is a directory"), std::string::npos) << message;
}
