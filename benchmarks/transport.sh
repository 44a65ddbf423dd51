#!/usr/bin/env bash
# Issue 17: what one LCM udpm process pays for traffic it did not subscribe to.
# A flooder publishes B-byte messages on FLOOD at R messages/s; beside it, listeners (each its own
# process, for S seconds) report their CPU: subscribed to exactly another channel, to nothing, to
# FLOOD itself; on another port of the same group; on another group of the same port (Linux
# delivers a group's datagrams to every socket bound to the port once any socket joined it:
# IP_MULTICAST_ALL). One JSON line per listener on stdout.
#
# Usage: benchmarks/transport.sh BUILD_DIR [RATES] [BYTES] [SECONDS] [URL_QUERY]
set -uo pipefail
BUILD=${1:-build}
RATES=${2:-"0 1000 4000 16000"}
BYTES=${3:-300}
S=${4:-8}
Q=${5:-ttl=0}
T="$BUILD/benchmarks/lcm_transport"
G1=239.255.76.67 G2=239.255.76.68 P1=7860 P2=7861
for R in $RATES; do
  "$T" flood --url "udpm://$G1:$P1?$Q" --channel FLOOD --rate "$R" --bytes "$BYTES" --seconds $((S + 2)) >/dev/null &
  f1=$!
  # a listener on G2:P1 that joins G2, and a flooder on G2 for the cross-group case
  "$T" flood --url "udpm://$G2:$P1?$Q" --channel FLOOD2 --rate "$R" --bytes "$BYTES" --seconds $((S + 2)) >/dev/null &
  f2=$!
  sleep 0.5
  pids=()
  run() { local tag=$1; shift; ( out=$("$T" listen --seconds "$S" "$@"); echo "{\"rate\": $R, \"bytes\": $BYTES, \"case\": \"$tag\", ${out#\{}" ) & pids+=($!); }
  run other_channel --url "udpm://$G1:$P1?$Q" --channel OTHER
  run no_subscription --url "udpm://$G1:$P1?$Q" --none
  run flood_channel --url "udpm://$G1:$P1?$Q" --channel FLOOD
  run other_port --url "udpm://$G1:$P2?$Q" --channel FLOOD
  run g2_member --url "udpm://$G2:$P1?$Q" --channel FLOOD2
  run regex_all --url "udpm://$G1:$P1?$Q" --channel '.*'
  for p in "${pids[@]}"; do wait "$p"; done
  wait $f1 $f2
done
