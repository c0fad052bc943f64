#include "app/StillTurns.h"

namespace inkgraph {

void StillTurns::enter(std::size_t still) {
    std::unique_lock<std::mutex> lock(mMutex);
    const std::thread::id self = std::this_thread::get_id();
    if (mHeld && mHolder == still && mHolderThread == self) return;
    mChanged.wait(lock, [this, still] { return !mHeld && (mStopped || mNext >= still); });
    mHeld = true;
    mHolder = still;
    mHolderThread = self;
}

void StillTurns::leave(std::size_t still) {
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        if (!mHeld || mHolder != still || mHolderThread != std::this_thread::get_id()) return;
        mHeld = false;
        if (!mStopped && mNext <= still) mNext = still + 1;
    }
    mChanged.notify_all();
}

bool StillTurns::isDue(std::size_t still) {
    const std::lock_guard<std::mutex> lock(mMutex);
    return !mHeld && mNext >= still;
}

bool StillTurns::stop(std::exception_ptr error) {
    bool first = false;
    {
        const std::lock_guard<std::mutex> lock(mMutex);
        mStopped = true;
        if (mFirstError == nullptr) mFirstError = error;
        first = error != nullptr && error == mFirstError;
    }
    mChanged.notify_all();
    return first;
}

std::exception_ptr StillTurns::firstError() {
    const std::lock_guard<std::mutex> lock(mMutex);
    return mFirstError;
}

bool StillTurns::stopped() {
    const std::lock_guard<std::mutex> lock(mMutex);
    return mStopped;
}

} // namespace inkgraph
