#include "app/RecentModel.h"

#include <sys/stat.h>

#include <utility>

namespace inkgraph {

namespace {

std::int64_t nanosecondsOf(const timespec& time) { return std::int64_t(time.tv_sec) * 1000000000 + time.tv_nsec; }

} // namespace

std::optional<RecentModel::Key> RecentModel::keyOf(const StillRequest& request) {
    struct stat file {};
    if (::stat(request.modelPath.c_str(), &file) != 0 || !S_ISREG(file.st_mode)) return std::nullopt;
    Key key;
    key.modelPath = request.modelPath;
    key.device = std::uint64_t(file.st_dev);
    key.inode = std::uint64_t(file.st_ino);
    key.size = std::int64_t(file.st_size);
    key.modifiedNanoseconds = nanosecondsOf(file.st_mtim);
    // The change time moves with every write and rename, also where a writer sets the modification time back.
    key.changedNanoseconds = nanosecondsOf(file.st_ctim);
    key.options = loadOptionsOf(request);
    return key;
}

RecentModel::Model RecentModel::find(const std::optional<Key>& key) const {
    if (!key || !mKey || !(*key == *mKey)) return {};
    return mModel;
}

void RecentModel::remember(const std::optional<Key>& key, Model model) {
    if (!key || !model.scene) {
        forget();
        return;
    }
    mKey = key;
    mModel = std::move(model);
}

void RecentModel::forget() {
    mKey.reset();
    mModel = {};
}

} // namespace inkgraph
