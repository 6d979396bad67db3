#pragma once
// Helpers shared by the meshio tests that read the exporters' series back with VTK: fresh output
// folders, whole files, .pvd indexes and .vtp files.
#include <catch2/catch.hpp>

#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace meshiotest {

namespace fs = std::filesystem;

/// An empty folder of the system's temporary folder, named after `name` and this process.
inline fs::path freshDir(const std::string& name) {
    fs::path d = fs::temp_directory_path() / ("fascia-meshio-test-" + name + "-" + std::to_string(getpid()));
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

/// A file's bytes.
inline std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The names of the files in a folder, sorted.
inline std::vector<std::string> fileNames(const fs::path& dir) {
    std::vector<std::string> names;
    for (auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// One DataSet of a .pvd: its timestep, part and file.
struct PvdEntry {
    double t;
    int part;
    std::string file;
};

/// The DataSets a .pvd lists, in order, parsed by VTK's XML parser.
inline std::vector<PvdEntry> pvdEntries(const fs::path& pvd) {
    vtkNew<vtkXMLDataParser> parser;
    parser->SetFileName(pvd.string().c_str());
    REQUIRE(parser->Parse() == 1);
    vtkXMLDataElement* root = parser->GetRootElement();
    REQUIRE(root);
    CHECK(std::string(root->GetName()) == "VTKFile");
    CHECK(std::string(root->GetAttribute("type")) == "Collection");
    vtkXMLDataElement* c = root->FindNestedElementWithName("Collection");
    REQUIRE(c);
    std::vector<PvdEntry> entries;
    for (int i = 0; i < c->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* e = c->GetNestedElement(i);
        REQUIRE(e->GetAttribute("timestep"));
        REQUIRE(e->GetAttribute("part"));
        entries.push_back({std::stod(e->GetAttribute("timestep")), std::stoi(e->GetAttribute("part")), e->GetAttribute("file")});
    }
    return entries;
}

/// The file names a .pvd lists, in order.
inline std::vector<std::string> pvdFiles(const fs::path& pvd) {
    std::vector<std::string> files;
    for (const PvdEntry& e : pvdEntries(pvd)) files.push_back(e.file);
    return files;
}

/// A .vtp file read by VTK's own reader (null on failure).
inline vtkSmartPointer<vtkPolyData> readVtp(const fs::path& file) {
    vtkNew<vtkXMLPolyDataReader> reader;
    reader->SetFileName(file.string().c_str());
    reader->Update();
    if (reader->GetErrorCode() != 0) return nullptr;
    return reader->GetOutput();
}

} // namespace meshiotest
