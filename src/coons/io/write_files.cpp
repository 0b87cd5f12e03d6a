#include "write_files.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "coons/io/input_error.h"

namespace coons {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = path + ".part";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, "", "cannot create the file");
    write(out);
    out.flush();
    if (!out) {
      out.close();
      std::remove(temporary.c_str());
      throw InputError(path, "", "writing failed");
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  if (ec) {
    std::remove(temporary.c_str());
    throw InputError(path, "", "cannot rename into place: " + ec.message());
  }
}

}  // namespace coons
