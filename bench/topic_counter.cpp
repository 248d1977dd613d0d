// Benchmark sink for bench/sensors_rtf.py: subscribes to the given topics with a deep queue (so that it
// never drops a message itself) and, when interrupted, prints per topic how many messages carry a
// header stamp inside the window [s of sim time] written in <window file> as "t0 t1" (t0 excluded), after
// counting every message that arrives until 0.3 s of quiet.
// Every counted type starts with std_msgs/Header (seq, stamp.sec, stamp.nsec, frame_id).
// Built by sensors_rtf.py with g++ (it needs no catkin target):
//   topic_counter <window file> <queue size> <topic>...
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <topic_tools/shape_shifter.h>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <vector>

namespace {
volatile std::sig_atomic_t g_stop = 0;
void onSigint(int) {
  g_stop = 1;
}
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "topic_counter", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSigint);
  if (argc < 4) {
    std::fprintf(stderr, "usage: topic_counter <window file> <queue size> <topic>...\n");
    return 2;
  }
  ros::NodeHandle nh;
  const std::string window_file = argv[1];
  const int queue = std::atoi(argv[2]);
  std::mutex mutex;
  std::map<std::string, std::vector<double>> stamps;  // [s]
  std::vector<ros::Subscriber> subs;
  for (int i = 3; i < argc; ++i) {
    const std::string topic = argv[i];
    stamps[topic].reserve(1 << 20);
    boost::function<void(const ros::MessageEvent<topic_tools::ShapeShifter const>&)> cb =
        [&, topic](const ros::MessageEvent<topic_tools::ShapeShifter const>& e) {
          const auto& m = *e.getConstMessage();
          std::vector<std::uint8_t> buf(m.size());
          ros::serialization::OStream out(buf.data(), static_cast<std::uint32_t>(buf.size()));
          m.write(out);
          std::uint32_t sec = 0, nsec = 0;
          if (buf.size() >= 12) {
            std::memcpy(&sec, buf.data() + 4, 4);
            std::memcpy(&nsec, buf.data() + 8, 4);
          }
          std::lock_guard<std::mutex> lock(mutex);
          stamps[topic].push_back(sec + 1e-9 * nsec);
        };
    subs.push_back(nh.subscribe<topic_tools::ShapeShifter>(topic, queue, cb, ros::VoidConstPtr(),
                                                           ros::TransportHints().tcpNoDelay()));
  }
  // Not ros::spin(): its SIGINT handler shuts ROS down and drops the callbacks still queued, so a message the
  // kernel had already handed over (which lockstep_wait_subscribers counts as taken) could go uncounted. Here
  // SIGINT only ends the loop; then the queue is drained until nothing more has come for 0.3 s.
  while (!g_stop)
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
  const auto total = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    std::size_t n = 0;
    for (const auto& kv : stamps)
      n += kv.second.size();
    return n;
  };
  std::size_t seen = total();
  ros::WallTime quiet = ros::WallTime::now();
  while (ros::WallTime::now() - quiet < ros::WallDuration(0.3)) {
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.05));
    const std::size_t now = total();
    if (now != seen) {
      seen = now;
      quiet = ros::WallTime::now();
    }
  }
  double t0 = 0.0, t1 = 0.0;
  std::ifstream(window_file) >> t0 >> t1;
  for (const auto& kv : stamps) {
    long n = 0;
    for (double s : kv.second)
      n += (s > t0 + 1e-9 && s <= t1 + 1e-9) ? 1 : 0;
    std::printf("%s %ld\n", kv.first.c_str(), n);
  }
  return 0;
}
