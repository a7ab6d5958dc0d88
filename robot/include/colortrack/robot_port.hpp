// SPDX-License-Identifier: LGPL-2.1-or-later
// Where robotctl's bytes go: a file, FIFO, pseudo-terminal, stdout or a serial port, behind one interface
// the command writer uses (tests give it a fake).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "colortrack/choice.hpp"
#include "colortrack/status.hpp"

struct sp_port;

namespace robotctl {

enum class WriteResult { Written, Busy, Failed };

class Port {
 public:
  virtual ~Port() = default;
  // Opens (or reopens) the port; why not, naming what to fix.
  virtual colortrack::Status open() = 0;
  virtual void close() = 0;
  virtual bool isOpen() const = 0;
  // Writes all of `bytes` within `timeoutMs` (> 0). Busy: the reader did not take them all in time; `written`
  // says how many went out (a frame may be cut: the caller sends the rest before anything else).
  virtual WriteResult write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &written,
                            std::string &why) = 0;
  virtual std::string describe() const = 0;
  // What the other end sent, without waiting (MAVLink's heartbeats, for the link state): at most `capacity`
  // bytes into `buffer`, `received` 0 when nothing is there. False: the link failed (over a connected UDP
  // socket a peer's "port unreachable" may show here before a write sees it). Ports that read nothing back
  // keep this default.
  virtual bool receive(std::uint8_t * /*buffer*/, std::size_t /*capacity*/, std::size_t &received,
                       std::string & /*why*/) {
    received = 0;
    return true;
  }
};

// A file, FIFO, pseudo-terminal or stdout ("-"), written without blocking. Only the first open creates (a
// regular file, emptied); a reopen waits for the kind of file the first open found.
class FilePort : public Port {
 public:
  explicit FilePort(std::string path) : path_(std::move(path)) {}
  ~FilePort() override { close(); }

  colortrack::Status open() override;
  void close() override;
  bool isOpen() const override { return fd_ >= 0; }
  WriteResult write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &written,
                    std::string &why) override;
  std::string describe() const override;

 private:
  bool openWithReason(std::string &why);

  std::string path_;
  int fd_ = -1;
  bool openedBefore_ = false;
  mode_t kind_ = 0;  // S_IFMT bits of what the first open found (a reopen needs the same kind)
};

// The serial settings libserialport understands; the element maps its enums onto these.
enum class Parity { None, Odd, Even, Mark, Space };
inline constexpr colortrack::Choice<Parity> kParities[] = {
    {Parity::None, "none", "None"}, {Parity::Odd, "odd", "Odd"},       {Parity::Even, "even", "Even"},
    {Parity::Mark, "mark", "Mark"}, {Parity::Space, "space", "Space"},
};
enum class FlowControl { None, XonXoff, RtsCts, DtrDsr };
inline constexpr colortrack::Choice<FlowControl> kFlowControls[] = {
    {FlowControl::None, "none", "None"},
    {FlowControl::XonXoff, "xonxoff", "Software (XON/XOFF)"},
    {FlowControl::RtsCts, "rtscts", "Hardware (RTS/CTS)"},
    {FlowControl::DtrDsr, "dtrdsr", "Hardware (DTR/DSR)"},
};

struct SerialConfig {
  std::string device;
  unsigned baudRate = 9600;
  int dataBits = 8, stopBits = 1;
  Parity parity = Parity::None;
  FlowControl flowControl = FlowControl::None;
};

// A serial port through libserialport.
class SerialPort : public Port {
 public:
  explicit SerialPort(SerialConfig config) : config_(std::move(config)) {}
  ~SerialPort() override { close(); }

  colortrack::Status open() override;
  void close() override;
  bool isOpen() const override { return port_ != nullptr; }
  WriteResult write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &written,
                    std::string &why) override;
  std::string describe() const override { return "serial port '" + config_.device + "' (property 'device')"; }

 private:
  bool openWithReason(std::string &why);
  SerialConfig config_;
  sp_port *port_ = nullptr;
};

}  // namespace robotctl
