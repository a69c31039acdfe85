// Directory listings for dataset loaders: names sorted the way frame and camera numbers
// are meant (numbers within names compare as numbers), without exceptions.
#ifndef M4D_ENCODER_DATASET_FILE_LISTING_H_
#define M4D_ENCODER_DATASET_FILE_LISTING_H_

#include <string>
#include <vector>

#include "sdk/src/common/status.h"

namespace m4d {

bool IsDirectory(const std::string& path);
bool IsRegularFile(const std::string& path);

// Natural order: runs of digits compare as numbers ("cam2" before "cam10", "9.png" before
// "10.png"), the rest character by character.
bool FrameNameLess(const std::string& a, const std::string& b);

enum class EntryKind { kFiles, kDirectories };

// Names (not paths) of the files or directories in `dir`, sorted by FrameNameLess.
// M4D_ERR_INVALID_ARG when the directory cannot be read.
Status ListDirectory(const std::string& dir, EntryKind kind, std::vector<std::string>* names);

// Names of the PNG and JPEG files (by extension, any case) in `dir`, sorted by FrameNameLess.
Status ListImageFiles(const std::string& dir, std::vector<std::string>* names);

}  // namespace m4d

#endif  // M4D_ENCODER_DATASET_FILE_LISTING_H_
