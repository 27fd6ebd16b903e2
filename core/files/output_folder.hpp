// An output folder a command creates when it is missing (`decode --batch -o DIR`): checked by
// core/files/output_set check_output_folder (a file, a device or a pipe under that name is
// refused, naming the flag), created with its missing parents, and removed again, each level it
// created, when the run ends without writing into it. A failed run then leaves the file system
// as it found it, as the commands that write into an existing folder do.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace pinmask {

class CreatedOutputFolder {
  public:
    // Throws InvalidInput naming `flag` (check_output_folder's rules). Creates nothing yet.
    CreatedOutputFolder(std::filesystem::path path, std::string flag);
    CreatedOutputFolder(const CreatedOutputFolder&) = delete;
    CreatedOutputFolder& operator=(const CreatedOutputFolder&) = delete;
    // Removes the folders create() made, innermost first, while each is empty; unless kept.
    ~CreatedOutputFolder();

    // Creates the folder and its missing parents (remembering which it made). RuntimeFailure
    // naming the flag, the path and the system's reason when one cannot be made.
    void create();
    // The run wrote its files: the folder stays whatever happens next.
    void keep() { created_.clear(); }
    const std::filesystem::path& path() const { return path_; }

  private:
    std::filesystem::path path_;
    std::string flag_;
    std::vector<std::filesystem::path> created_;  // outermost first
};

}  // namespace pinmask
