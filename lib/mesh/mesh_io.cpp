#include "mesh/mesh_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include "base/errors.hpp"
#include "mesh/edge_incidence.hpp"
#include "mesh/formats/mesh_formats.hpp"

namespace sculpt {
namespace {

namespace fs = std::filesystem;

std::string errno_text(int err) { return std::strerror(err); }

/// Closes and removes the temporary file unless released.
class TempFile {
 public:
  TempFile(int fd, fs::path path) : fd_(fd), path_(std::move(path)) {}
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!released_) ::unlink(path_.c_str());
  }
  [[nodiscard]] int fd() const { return fd_; }
  [[nodiscard]] const fs::path& path() const { return path_; }
  int close() {
    const int r = ::close(fd_);
    fd_ = -1;
    return r;
  }
  void release() { released_ = true; }

 private:
  int fd_;
  fs::path path_;
  bool released_ = false;
};

}  // namespace

// Write to a hidden temporary beside the target, fsync, rename over the target (mesh_io.hpp).
void write_file_atomically(const fs::path& path, std::string_view data) {
  const std::string target = path.string();
  if (path.filename().empty()) throw IoError(target, "cannot write: the path names no file");
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  static std::atomic<unsigned> counter{0};
  int fd = -1;
  fs::path tmp;
  for (int attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    std::string name = ".";  // hidden, and ends in .tmp (ignored by git)
    name += path.filename().string();
    name += ".sculpt-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".tmp";
    tmp = dir / name;
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST)
      throw IoError(target, "cannot create a temporary file in '" + dir.string() +
                                "': " + errno_text(errno));
  }
  if (fd < 0) throw IoError(target, "cannot create a temporary file in '" + dir.string() + "'");
  TempFile file(fd, tmp);
  size_t done = 0;
  while (done < data.size()) {
    const ssize_t n = ::write(file.fd(), data.data() + done, data.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      throw IoError(target, "write failed after " + std::to_string(done) + " of " +
                                std::to_string(data.size()) + " bytes: " +
                                errno_text(n < 0 ? errno : EIO) + " (previous file left as it was)");
    done += static_cast<size_t>(n);
  }
  if (::fsync(file.fd()) != 0)
    throw IoError(target, "cannot flush to disk: " + errno_text(errno));
  if (file.close() != 0) throw IoError(target, "cannot close the written file: " + errno_text(errno));
  if (::rename(tmp.c_str(), path.c_str()) != 0)
    throw IoError(target, "cannot replace the file: " + errno_text(errno));
  file.release();
}

namespace {

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string(), "cannot open for reading: " + errno_text(errno));
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw IoError(path.string(), "is a directory, not a mesh file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw IoError(path.string(), "read failed: " + errno_text(errno));
  return std::move(buffer).str();
}

void check_writable(const PolygonMesh& mesh, MeshFormat format, bool binary) {
  check_face_indices(mesh, "write_mesh");
  for (size_t v = 0; v < mesh.vertices.size(); ++v) {
    const Eigen::Vector3d& p = mesh.vertices[v];
    if (!p.allFinite())
      throw InvalidInput("write_mesh: vertex " + std::to_string(v) + " has a non-finite coordinate");
    if (((format == MeshFormat::Stl && binary) || format == MeshFormat::Glb) &&
        p.cwiseAbs().maxCoeff() > static_cast<double>(std::numeric_limits<float>::max()))
      throw InvalidInput("write_mesh: vertex " + std::to_string(v) + " is beyond the float32 range of " +
                         (format == MeshFormat::Glb ? "glTF" : "binary STL"));
  }
}

}  // namespace

MeshFormat mesh_format_from_path(const fs::path& path) {
  std::string ext = path.extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".off") return MeshFormat::Off;
  if (ext == ".obj") return MeshFormat::Obj;
  if (ext == ".stl") return MeshFormat::Stl;
  if (ext == ".ply") return MeshFormat::Ply;
  if (ext == ".om") return MeshFormat::Om;
  if (ext == ".3mf") return MeshFormat::ThreeMf;
  if (ext == ".glb") return MeshFormat::Glb;
  throw IoError(path.string(), "unknown mesh format '" + ext + "' (use .off, .obj, .stl, .ply, .om, .3mf or .glb)");
}

std::string encode_mesh(const PolygonMesh& mesh, MeshFormat format, bool binary) {
  check_writable(mesh, format, binary);
  switch (format) {
    case MeshFormat::Off: return mesh::detail::encode_off(mesh);
    case MeshFormat::Obj: return mesh::detail::encode_obj(mesh);
    case MeshFormat::Stl: return mesh::detail::encode_stl(mesh, binary);
    case MeshFormat::Ply: return mesh::detail::encode_ply(mesh, binary);
    case MeshFormat::Om: return mesh::detail::encode_om(mesh);
    case MeshFormat::ThreeMf: return mesh::detail::encode_3mf(mesh);
    case MeshFormat::Glb:
      return mesh::detail::encode_glb(mesh);
    case MeshFormat::Auto: break;
  }
  throw InvalidInput("encode_mesh: the format must be given (not Auto)");
}

DisplayArrays display_arrays(const PolygonMesh& mesh) {
  check_writable(mesh, MeshFormat::Glb, false);
  return mesh::detail::triangle_arrays(mesh);
}

std::string encode_glb_for_display(const DisplayArrays& arrays) { return mesh::detail::encode_display_glb(arrays); }

std::string encode_glb_for_display(const PolygonMesh& mesh) { return encode_glb_for_display(display_arrays(mesh)); }

PolygonMesh decode_mesh(std::string_view data, MeshFormat format, const std::string& name) {
  switch (format) {
    case MeshFormat::Off: return mesh::detail::decode_off(data, name);
    case MeshFormat::Obj: return mesh::detail::decode_obj(data, name);
    case MeshFormat::Stl: return mesh::detail::decode_stl(data, name);
    case MeshFormat::Ply: return mesh::detail::decode_ply(data, name);
    case MeshFormat::Om: return mesh::detail::decode_om(data, name);
    case MeshFormat::ThreeMf: return mesh::detail::decode_3mf(data, name);
    case MeshFormat::Glb:
      return mesh::detail::decode_glb(data, name);
    case MeshFormat::Auto: break;
  }
  throw InvalidInput("decode_mesh: the format must be given (not Auto)");
}

void write_mesh(const PolygonMesh& mesh, const fs::path& path, WriteOptions options) {
  const MeshFormat format =
      options.format == MeshFormat::Auto ? mesh_format_from_path(path) : options.format;
  write_file_atomically(path, encode_mesh(mesh, format, options.binary));
}

PolygonMesh read_mesh(const fs::path& path, ReadOptions options) {
  const MeshFormat format =
      options.format == MeshFormat::Auto ? mesh_format_from_path(path) : options.format;
  const std::string data = read_file(path);
  return decode_mesh(data, format, path.string());
}

}  // namespace sculpt
