#pragma once
// An eventfd a device thread polls beside its device, so Stop() can wake it out of poll() at once
// instead of waiting for the next edge or timeout. Owned by the object that owns the thread.

namespace sas::platform {

class WakeEvent {
 public:
  WakeEvent() = default;
  ~WakeEvent() { Close(); }
  WakeEvent(const WakeEvent&) = delete;
  WakeEvent& operator=(const WakeEvent&) = delete;

  bool Open();    // false if the kernel refuses an eventfd
  void Signal();  // wakes the poller; harmless when closed
  void Close();
  int fd() const { return fd_; }  // poll it for POLLIN; -1 when closed

 private:
  int fd_ = -1;
};

}  // namespace sas::platform
