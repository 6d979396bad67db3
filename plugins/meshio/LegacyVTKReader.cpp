// The legacy VTK reader: our own parser of .vtk unstructured grids (see LegacyVTKReader.h for why).
// The sections are read in file order into plain arrays, every count bounded by the bytes left in
// the file (LegacyVTKScanner), then checked against each other and turned into the mesh.
#include "LegacyVTKReader.h"

#include "LegacyVTKScanner.h"
#include "ReaderSupport.h"
#include "VTKCells.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace fascia::meshio::detail {
namespace {

/// A cell or point data array of the file.
struct DataArray {
    std::string name;
    long long components = 1, tuples = 0;
    std::vector<double> values;
};

/// Array names may encode characters as %XX (VTK's writer does for spaces).
std::string decodeName(std::string_view w) {
    std::string out;
    for (size_t i = 0; i < w.size(); ++i) {
        if (w[i] == '%' && i + 2 < w.size() && std::isxdigit((unsigned char)w[i + 1]) &&
            std::isxdigit((unsigned char)w[i + 2])) {
            out += char(std::stoi(std::string(w.substr(i + 1, 2)), nullptr, 16));
            i += 2;
        } else {
            out += w[i];
        }
    }
    return out;
}

const char* const kLayout =
    "; a legacy VTK file starts with '# vtk DataFile Version x.x', a title line, ASCII or BINARY, and "
    "'DATASET UNSTRUCTURED_GRID'";

class LegacyVtkReader {
public:
    LegacyVtkReader(std::string_view text, const std::string& path, MeshBuilder& b)
        : m_sc(text, path), m_path(path), m_b(b) {}

    void read() {
        header();
        while (!m_sc.atEnd()) section(m_sc.keyword("next section"));
        build();
    }

private:
    // ---- the header and the sections, in file order --------------------------------------------
    void header() {
        std::string_view line;
        if (!m_sc.headerLine(line) || LegacyVtkScanner::lower(line).rfind("# vtk datafile version", 0) != 0)
            m_sc.failHere("'" + m_path + "' is not a VTK legacy file" + kLayout);
        std::string_view v = line.substr(22);
        while (!v.empty() && (v.front() == ' ' || v.front() == '\t')) v.remove_prefix(1);
        const auto dot = v.find('.');
        int minor = 0;
        const bool ok = dot != std::string_view::npos &&
                        std::from_chars(v.data(), v.data() + dot, m_major).ptr == v.data() + dot &&
                        std::from_chars(v.data() + dot + 1, v.data() + v.size(), minor).ptr == v.data() + v.size();
        if (!ok || m_major < 1 || m_major > 5)
            m_sc.failHere("unsupported legacy VTK file version " + quoted(v) + ": versions 1.0 to 4.2 and 5.1 are read");
        if (!m_sc.headerLine(line)) m_sc.failHere("the file ends after its first line: the title line is missing" + std::string(kLayout));
        if (!m_sc.headerLine(line)) m_sc.failHere("the file ends after its title line: ASCII or BINARY is missing");
        const std::string format = LegacyVtkScanner::lower(line);
        if (format.rfind("binary", 0) == 0)
            m_sc.setBinary(true);
        else if (format.rfind("ascii", 0) != 0)
            m_sc.failHere("the third line is " + quoted(line) + ", expected ASCII or BINARY" + kLayout);
        if (m_sc.keyword("DATASET line") != "dataset")
            m_sc.failHere("expected DATASET UNSTRUCTURED_GRID after ASCII or BINARY" + std::string(kLayout));
        const std::string type = LegacyVtkScanner::lower(m_sc.wordOnLine());
        if (type != "unstructured_grid") {
            const char* cls = type == "polydata"            ? " (vtkPolyData)"
                              : type == "structured_points" ? " (vtkStructuredPoints)"
                              : type == "structured_grid"   ? " (vtkStructuredGrid)"
                              : type == "rectilinear_grid"  ? " (vtkRectilinearGrid)"
                                                            : "";
            m_sc.failHere("'" + m_path + "' holds a DATASET " + quoted(type) + cls +
                          "; only DATASET UNSTRUCTURED_GRID has volume cells (tetrahedra, hexahedra)");
        }
        m_sc.endLine();
    }

    void section(const std::string& key) {
        if (key == "points") readPoints();
        else if (key == "cells") m_major >= 5 ? readCells5() : readCellsLegacy();
        else if (key == "cell_types") readCellTypes();
        else if (key == "cell_data" || key == "point_data") startAttributes(key == "cell_data");
        else if (key == "field" && !m_attributes) readField(false);
        else if (key == "metadata") m_sc.skipToEmptyLine();
        else if (m_attributes) readAttribute(key);
        else
            m_sc.failHere("unexpected " + quoted(key) +
                          ": an unstructured grid has the sections POINTS, CELLS, CELL_TYPES, CELL_DATA and POINT_DATA");
    }

    VtkDataType dataType(const char* what) {
        const std::string_view w = m_sc.wordOnLine();
        if (w.empty()) m_sc.failHere(std::string("the line ends before the data type of ") + what);
        VtkDataType t;
        if (!parseVtkDataType(w, t))
            m_sc.failHere("unsupported data type " + quoted(w) + " of " + what +
                          ": supported are the integer types, float and double");
        return t;
    }
    void once(bool& seen, const char* key) {
        if (seen) m_sc.failHere(std::string("a second ") + key + " section: the file has one");
        seen = true;
    }

    void readPoints() {
        once(m_havePoints, "POINTS");
        m_nPoints = m_sc.count("number of points");
        const VtkDataType t = dataType("POINTS");
        m_sc.requireRoom(m_nPoints, 3, t, "POINTS");
        m_points = m_sc.reals(3 * m_nPoints, t, "POINTS", 3, &m_pointWhere);
    }

    /// Versions before 5: "CELLS n size", then per cell its point count and its point indices.
    void readCellsLegacy() {
        once(m_haveCells, "CELLS");
        const long long n = m_sc.count("number of cells");
        const long long size = m_sc.count("CELLS size (number of values)");
        m_cellsWhere = m_sc.where();
        const VtkDataType int32{"int", 4, false, true};
        if (n > size) m_sc.failHere("CELLS announces " + plural(n, "cell") + " in " + plural(size, "value") +
                                    ": each cell needs at least one value (its point count)");
        std::vector<long long> wheres;
        const std::vector<long long> v = m_sc.integers(size, int32, "CELLS", &wheres);
        m_offsets.assign(1, 0);
        m_offsets.reserve(size_t(n) + 1);
        m_cellWhere.reserve(size_t(n));
        m_conn.reserve(size_t(size - n));
        m_connWhere.reserve(size_t(size - n));
        long long pos = 0;
        for (long long c = 0; c < n; ++c) {
            if (pos >= size)
                m_sc.failAt(m_cellsWhere, "CELLS size " + std::to_string(size) + " is used up after " +
                                              std::to_string(c) + " of the " + plural(n, "cell") + ": the counts lie");
            const long long npts = v[size_t(pos)];
            if (npts < 0 || npts > size - pos - 1)
                m_sc.failAt(wheres[size_t(pos)], "cell " + std::to_string(c) + " announces " + std::to_string(npts) +
                                                     " points, but only " + std::to_string(size - pos - 1) +
                                                     " values of the CELLS size " + std::to_string(size) + " are left");
            m_cellWhere.push_back(wheres[size_t(pos)]);
            for (long long k = 0; k < npts; ++k) {
                m_conn.push_back(v[size_t(pos + 1 + k)]);
                m_connWhere.push_back(wheres[size_t(pos + 1 + k)]);
            }
            pos += 1 + npts;
            m_offsets.push_back(pos - c - 1);
        }
        if (pos != size)
            m_sc.failAt(m_cellsWhere, "CELLS announces a size of " + std::to_string(size) + " values, but its " +
                                          plural(n, "cell") + " use " + std::to_string(pos) + ": the counts lie");
        m_nCells = n;
    }

    /// Version 5: "CELLS nOffsets nConnectivity", an OFFSETS array and a CONNECTIVITY array.
    void readCells5() {
        once(m_haveCells, "CELLS");
        const long long nOffsets = m_sc.count("number of offsets");
        const long long nConn = m_sc.count("connectivity size");
        m_cellsWhere = m_sc.where();
        if (m_sc.keyword("OFFSETS array") != "offsets") m_sc.failHere("expected OFFSETS after CELLS (a version 5 file)");
        std::vector<long long> offsetWhere;
        m_offsets = m_sc.integers(nOffsets, dataType("OFFSETS"), "OFFSETS", &offsetWhere);
        if (m_sc.keyword("CONNECTIVITY array") != "connectivity")
            m_sc.failHere("expected CONNECTIVITY after the OFFSETS (a version 5 file)");
        m_conn = m_sc.integers(nConn, dataType("CONNECTIVITY"), "CONNECTIVITY", &m_connWhere);
        if (nOffsets == 0) {
            if (nConn != 0) m_sc.failAt(m_cellsWhere, "CELLS has no offsets but " + plural(nConn, "connectivity value"));
            m_offsets.assign(1, 0);
            offsetWhere.assign(1, m_cellsWhere);
        }
        if (m_offsets[0] != 0) m_sc.failAt(offsetWhere[0], "the first offset is " + std::to_string(m_offsets[0]) + ", not 0");
        for (size_t i = 1; i < m_offsets.size(); ++i)
            if (m_offsets[i] < m_offsets[i - 1] || m_offsets[i] > nConn)
                m_sc.failAt(offsetWhere[i], "offset " + std::to_string(i) + " is " + std::to_string(m_offsets[i]) +
                                                (m_offsets[i] < m_offsets[i - 1]
                                                     ? ", less than the offset before it (" + std::to_string(m_offsets[i - 1]) +
                                                           "): offsets must not decrease"
                                                     : ", past the " + plural(nConn, "connectivity value")));
        if (m_offsets.back() != nConn)
            m_sc.failAt(offsetWhere.back(), "the last offset is " + std::to_string(m_offsets.back()) + ", but there are " +
                                                plural(nConn, "connectivity value") + ": the counts lie");
        m_nCells = (long long)m_offsets.size() - 1;
        m_cellWhere.assign(offsetWhere.begin(), offsetWhere.end() - 1);
    }

    void readCellTypes() {
        once(m_haveTypes, "CELL_TYPES");
        const long long n = m_sc.count("number of cell types");
        m_typesWhere = m_sc.where();
        m_types = m_sc.integers(n, {"int", 4, false, true}, "CELL_TYPES", &m_typeWhere);
    }

    // ---- CELL_DATA and POINT_DATA ---------------------------------------------------------------
    void startAttributes(bool cells) {
        bool& seen = cells ? m_haveCellData : m_havePointData;
        once(seen, cells ? "CELL_DATA" : "POINT_DATA");
        m_attributes = true;
        m_inCellData = cells;
        m_tuples = m_sc.count("number of values");
        if (cells) {
            m_cellDataWhere = m_sc.where();
            m_cellDataTuples = m_tuples;
        }
    }

    /// One attribute (SCALARS, VECTORS, ...) of n tuples: name, type and components per its keyword.
    void readAttribute(const std::string& key) {
        const std::string name = decodeName(m_sc.wordOnLine());
        if (name.empty()) m_sc.failHere(key + " needs a name");
        const VtkDataType uchar{"unsigned_char", 1, false, false};
        VtkDataType t;
        long long comps = 1;
        double scale = 1;
        if (key == "scalars") {
            t = dataType("SCALARS");
            const std::string_view c = m_sc.wordOnLine();
            if (!c.empty() && (std::from_chars(c.data(), c.data() + c.size(), comps).ptr != c.data() + c.size() ||
                               comps < 1 || comps > 4))
                m_sc.failHere("the number of SCALARS components " + quoted(c) + " must be 1 to 4");
            if (m_sc.keyword("LOOKUP_TABLE line") != "lookup_table")
                m_sc.failHere("SCALARS " + quoted(name) + " must be followed by a LOOKUP_TABLE line");
            m_sc.wordOnLine();  // the table's name
        } else if (key == "color_scalars") {
            comps = m_sc.count("number of COLOR_SCALARS components");
            t = m_sc.binary() ? uchar : VtkDataType{"float", 4, true, true};
            if (m_sc.binary()) scale = 1.0 / 255;
        } else if (key == "lookup_table") {
            const long long size = m_sc.count("LOOKUP_TABLE size");
            t = m_sc.binary() ? uchar : VtkDataType{"float", 4, true, true};
            m_sc.requireRoom(size, 4, t, "LOOKUP_TABLE");
            m_sc.reals(4 * size, t, "LOOKUP_TABLE");
            return;  // colours, not data
        } else if (key == "vectors" || key == "normals") {
            t = dataType(key == "vectors" ? "VECTORS" : "NORMALS");
            comps = 3;
        } else if (key == "tensors" || key == "tensors6") {
            t = dataType("TENSORS");
            comps = key == "tensors" ? 9 : 6;
        } else if (key == "texture_coordinates") {
            comps = m_sc.count("TEXTURE_COORDINATES dimension");
            if (comps < 1 || comps > 3) m_sc.failHere("TEXTURE_COORDINATES dimension must be 1 to 3");
            t = dataType("TEXTURE_COORDINATES");
        } else if (key == "global_ids" || key == "pedigree_ids") {
            t = dataType("GLOBAL_IDS");
        } else if (key == "field") {
            readField(m_inCellData, name);
            return;
        } else {
            m_sc.failHere("unexpected " + quoted(key) + " in " + (m_inCellData ? "CELL_DATA" : "POINT_DATA") +
                          ": expected SCALARS, VECTORS, NORMALS, TENSORS, TEXTURE_COORDINATES, COLOR_SCALARS or FIELD");
        }
        m_sc.requireRoom(m_tuples, comps, t, key + " " + quoted(name));
        DataArray a{name, comps, m_tuples, m_sc.reals(m_tuples * comps, t, key + " " + quoted(name))};
        if (scale != 1)
            for (auto& x : a.values) x *= scale;
        if (m_inCellData) m_cellArrays.push_back(std::move(a));
    }

    /// A FIELD block: "FIELD name nArrays", then per array "name components tuples type" and its data.
    void readField(bool keep, const std::string& fieldName = {}) {
        if (fieldName.empty()) m_sc.wordOnLine();  // the field's name, at the top level
        const long long nArrays = m_sc.count("number of FIELD arrays");
        m_sc.requireRoom(nArrays, 1, {"char", 1, false, true}, "FIELD");
        for (long long i = 0; i < nArrays; ++i) {
            const std::string name = decodeName(m_sc.word());
            if (name.empty()) m_sc.failHere("the file ends inside FIELD after " + std::to_string(i) + " of " +
                                            plural(nArrays, "array"));
            if (name == "NULL_ARRAY") continue;
            const long long comps = m_sc.count("number of components");
            const long long tuples = m_sc.count("number of tuples");
            const VtkDataType t = dataType("the FIELD array");
            m_sc.requireRoom(tuples, comps, t, "FIELD array " + quoted(name));
            DataArray a{name, comps, tuples, m_sc.reals(tuples * comps, t, "FIELD array " + quoted(name))};
            if (keep) m_cellArrays.push_back(std::move(a));
        }
    }

    // ---- the mesh --------------------------------------------------------------------------------
    void checkCounts() {
        if (m_nPoints <= 0 && m_nCells <= 0)
            fail(m_path, 0, "'" + m_path + "' has no points and no cells; is the file complete?");
        if (m_haveCells && !m_haveTypes)
            m_sc.failAt(m_cellsWhere, "the file has CELLS but no CELL_TYPES: the type of each cell is missing");
        if (m_haveTypes && (long long)m_types.size() != std::max(m_nCells, 0LL))
            m_sc.failAt(m_typesWhere, "CELL_TYPES has " + plural((long long)m_types.size(), "type") + ", but CELLS has " +
                                          plural(std::max(m_nCells, 0LL), "cell") + ": there must be one type per cell");
        if (m_haveCellData && m_tuplesOfCells() != std::max(m_nCells, 0LL))
            m_sc.failAt(m_cellDataWhere, "CELL_DATA has " + plural(m_tuplesOfCells(), "value") + ", but CELLS has " +
                                             plural(std::max(m_nCells, 0LL), "cell") + ": there must be one per cell");
        if (m_nPoints > INT_MAX) fail(m_path, 0, "'" + m_path + "' has more points than Fascia can index");
    }
    long long m_tuplesOfCells() const { return m_cellDataTuples; }

    const DataArray* groupArray() const {
        for (const char* gname : {"gmsh:physical", "CellEntityIds"})
            for (const auto& a : m_cellArrays)
                if (a.name == gname && a.components == 1 && a.tuples == m_nCells) return &a;
        return nullptr;
    }

    void build() {
        checkCounts();
        auto& mesh = m_b.mesh;
        const size_t np = size_t(std::max(m_nPoints, 0LL));
        mesh.points.resize(np);
        for (size_t i = 0; i < np; ++i) mesh.points[i] = Vec3(m_points[3 * i], m_points[3 * i + 1], m_points[3 * i + 2]);
        if (!m_sc.binary()) m_b.origin.nodeLine.assign(m_pointWhere.begin(), m_pointWhere.end());
        else m_b.origin.nodeByte = m_pointWhere;
        const DataArray* groups = groupArray();
        std::vector<int> nodes;
        for (long long c = 0; c < std::max(m_nCells, 0LL); ++c) {
            const long long type = m_types[size_t(c)];
            const long long first = m_offsets[size_t(c)], n = m_offsets[size_t(c) + 1] - first;
            nodes.resize(size_t(n));
            for (long long k = 0; k < n; ++k) {
                const long long v = m_conn[size_t(first + k)];
                if (v < 0 || v >= m_nPoints)
                    m_sc.failAt(m_connWhere[size_t(first + k)],
                                "cell " + std::to_string(c) + " names point " + std::to_string(v) + ", but the file has " +
                                    plural(m_nPoints, "point") + " (0-based indices 0 to " + std::to_string(m_nPoints - 1) + ")");
                nodes[size_t(k)] = int(v);
            }
            if (type < 0 || type > 255)
                m_sc.failAt(m_typeWhere[size_t(c)], "cell " + std::to_string(c) + " has the type " + std::to_string(type) +
                                                        ", which is no VTK cell type (0 to 255)");
            const int want = vtkKeptCellSize(int(type));
            if (want != 0 && n != want)
                m_sc.failAt(m_cellWhere[size_t(c)], "cell " + std::to_string(c) + " has type " + std::to_string(type) +
                                                        " (" + (type == kVtkTetra ? "tetrahedron" : type == kVtkTriangle ? "triangle" : "hexahedron") +
                                                        ") with " + plural(n, "point") + "; it must have " + std::to_string(want));
            int group = 0;
            if (groups) {
                const double g = groups->values[size_t(c)];
                if (!(std::fabs(g) <= INT_MAX))
                    m_sc.failAt(m_cellDataWhere, "the group " + formatNumber(g, 6) + " of cell " + std::to_string(c) + " in " +
                                                     groups->name + " is not a whole number in range");
                group = int(std::lround(g));
            }
            addVtkCell(m_b, c, int(type), nodes.data(), nodes.size(), group,
                       m_sc.binary() ? 0 : int(m_cellWhere[size_t(c)]), m_sc.binary() ? m_cellWhere[size_t(c)] : -1);
        }
        for (const auto& a : m_cellArrays)
            if (a.tuples == m_nCells) addVtkCellArray(m_b, a.name, int(a.components), a.values.data());
    }

    LegacyVtkScanner m_sc;
    const std::string& m_path;
    MeshBuilder& m_b;
    int m_major = 0;
    bool m_havePoints = false, m_haveCells = false, m_haveTypes = false, m_haveCellData = false, m_havePointData = false;
    long long m_nPoints = -1, m_nCells = -1;
    std::vector<double> m_points;
    std::vector<long long> m_pointWhere;
    std::vector<long long> m_offsets, m_conn, m_connWhere, m_cellWhere;  // cell c: m_conn[offsets[c], offsets[c + 1])
    long long m_cellsWhere = 0;
    std::vector<long long> m_types, m_typeWhere;
    long long m_typesWhere = 0;
    bool m_attributes = false, m_inCellData = false;
    long long m_tuples = 0, m_cellDataTuples = 0, m_cellDataWhere = 0;
    std::vector<DataArray> m_cellArrays;
};

} // namespace

void readLegacyVtk(const std::string& path, MeshBuilder& b) {
    b.origin.elementWord = "cell";
    b.report->format = "VTK legacy";
    const std::string text = readWholeFile(path, true);
    std::string_view view = text;
    LegacyVtkReader reader(view, path, b);
    reader.read();
}

} // namespace fascia::meshio::detail
