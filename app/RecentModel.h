#pragma once
/** @file The model a batch's session loaded last, kept for the stills after it that load the same file the same way
 *  (the views of --views, a list naming a model twice in a row): they take it instead of reading, parsing and
 *  welding the file again. A loaded scene is immutable (std::shared_ptr<const Scene>), so stills share it. */

#include "render/StillRenderer.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace inkgraph {

class RecentModel {
public:
    /** What a load depends on: the model's path, the file as it is on disk when the load starts (a file rewritten,
     *  replaced or touched in between is read again), and every load option of the request. */
    struct Key {
        std::string modelPath;
        std::uint64_t device = 0;
        std::uint64_t inode = 0;
        std::int64_t size = 0;
        std::int64_t modifiedNanoseconds = 0;
        std::int64_t changedNanoseconds = 0;
        LoadOptions options; ///< loadOptionsOf() the request
        bool operator==(const Key&) const = default;
    };

    /** A loaded model and what the stills drawing it derived from it whatever the view (the edge adjacency, the
     *  curvature, ...), which the next still of the model takes too. */
    struct Model {
        std::shared_ptr<const Scene> scene;
        std::shared_ptr<SceneDerivedData> derived;
    };

    /** The key of `request`'s load; none when its file cannot be examined (the load then says why). */
    static std::optional<Key> keyOf(const StillRequest& request);

    /** The model remembered for `key`, or an empty one (no key, or another load). */
    Model find(const std::optional<Key>& key) const;
    /** Keeps `model` as the one loaded for `key`, in place of the one before; nothing without a key or a scene. */
    void remember(const std::optional<Key>& key, Model model);
    /** Lets go of the model: the next still loads another, or its memory is wanted. */
    void forget();

private:
    std::optional<Key> mKey;
    Model mModel;
};

} // namespace inkgraph
