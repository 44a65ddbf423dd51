#!/bin/sh
# Runs LCM's lcm-spy on hapticd's streams, live or from a recorded log, with our message types
# built for Java so every channel is decoded. Installs the Debian 12 packages it needs (through
# ../setup.sh). Not part of the build or of `make test`. See docs/clients.md §10.
set -eu

usage() {
  cat <<'EOF'
usage: messages/lcm-spy.sh [options]

Generates Java classes for every messages/*.lcm (lcm-gen -j), compiles them into a jar and runs
LCM's lcm-spy (class lcm.spy.Spy in /usr/share/java/lcm.jar) with that jar on its classpath, so
it names the type of every THX_* channel and shows each message's fields (double-click a row).

  --lcm-url URL    the bus to watch (default udpm://239.255.76.67:7667?ttl=0, hapticd's default)
  --log FILE       watch a recorded LCM log instead of the bus (hapticd --record, lcm-logger):
                   lcm-spy reads it itself through LCM's file:// provider, nothing is published
  --speed X        with --log: playback speed (default 1 = the recorded pace)
  --out DIR        where the generated sources, classes and jar go (default build/lcm-java)
  --build-only     generate and compile the jar, print its path, do not start lcm-spy
  --fingerprints   print each Java type's fingerprint (compare with docs/messages.md §6)
  --no-install     do not install missing Debian packages: name them and fail
  -h, --help       this text

Installs when missing (apt-get, as root or with sudo): liblcm-java (lcm.jar), libjchart2d-java
(lcm-spy's charts), openjdk-17-jre (a JRE with X11 support) and openjdk-17-jdk-headless (javac).
lcm-spy is a window: it needs DISPLAY (on a machine without one: Xvfb :99 & DISPLAY=:99 ...).
Debian's /usr/bin/lcm-spy wrapper does not work with Java 17 (it passes -Xincgc); this script
runs the class directly.
EOF
}

die() {
  echo "lcm-spy.sh: error: $*" >&2
  exit 1
}

ROOT=$(cd "$(dirname "$0")/.." && pwd)
URL="udpm://239.255.76.67:7667?ttl=0"
LOG=""
SPEED=1
OUT="$ROOT/build/lcm-java"
MODE=spy
INSTALL=1

while [ $# -gt 0 ]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --lcm-url) [ $# -ge 2 ] || die "--lcm-url needs a URL"; URL=$2; shift ;;
    --lcm-url=*) URL=${1#*=} ;;
    --log) [ $# -ge 2 ] || die "--log needs a file"; LOG=$2; shift ;;
    --speed) [ $# -ge 2 ] || die "--speed needs a number"; SPEED=$2; shift ;;
    --out) [ $# -ge 2 ] || die "--out needs a directory"; OUT=$2; shift ;;
    --build-only) MODE=build ;;
    --fingerprints) MODE=fingerprints ;;
    --no-install) INSTALL="" ;;
    *) die "unknown option '$1' (see --help)" ;;
  esac
  shift
done

LCM_JAR=/usr/share/java/lcm.jar
CHART_JAR=/usr/share/java/jchart2d.jar
PACKAGES="liblcm-bin liblcm-java libjchart2d-java openjdk-17-jre openjdk-17-jdk-headless"
# shellcheck disable=SC2086 # one word per package
if [ -n "$INSTALL" ]; then
  "$ROOT/setup.sh" $PACKAGES || die "could not install the packages lcm-spy needs ($PACKAGES)"
else
  "$ROOT/setup.sh" --check $PACKAGES || die "missing packages (run without --no-install to install them)"
fi
for f in "$LCM_JAR" "$CHART_JAR"; do
  [ -f "$f" ] || die "$f is missing although its package is installed"
done
command -v javac >/dev/null 2>&1 || die "javac not found on PATH (openjdk-17-jdk-headless provides it)"

TYPES=$(for f in "$ROOT"/messages/*.lcm; do basename "$f" .lcm; done)
# Generate and compile when a .lcm file is newer than the jar (or the jar is absent).
JAR="$OUT/thx_msgs.jar"
if [ ! -f "$JAR" ] || [ -n "$(find "$ROOT/messages" -maxdepth 1 -name '*.lcm' -newer "$JAR")" ]; then
  rm -rf "$OUT/src" "$OUT/classes"
  mkdir -p "$OUT/src" "$OUT/classes"
  lcm-gen -j --jpath "$OUT/src" "$ROOT"/messages/*.lcm || die "lcm-gen -j failed"
  javac -nowarn -encoding UTF-8 -cp "$LCM_JAR" -d "$OUT/classes" "$OUT"/src/thx_msgs/*.java ||
    die "javac failed on the generated classes in $OUT/src"
  jar cf "$JAR.tmp" -C "$OUT/classes" . || die "could not write $JAR.tmp"
  mv "$JAR.tmp" "$JAR"
  echo "lcm-spy.sh: built $JAR from $(echo "$TYPES" | wc -w) types"
fi

case "$MODE" in
  build)
    echo "$JAR"
    exit 0
    ;;
  fingerprints)
    mkdir -p "$OUT/fingerprints"
    cat > "$OUT/fingerprints/Fingerprints.java" <<'EOF'
public class Fingerprints {
  public static void main(String[] names) throws Exception {
    for (String n : names) {
      long fp = Class.forName("thx_msgs." + n).getField("LCM_FINGERPRINT").getLong(null);
      System.out.printf("%-20s 0x%016x%n", n, fp);
    }
  }
}
EOF
    javac -d "$OUT/fingerprints" "$OUT/fingerprints/Fingerprints.java" || die "javac failed on Fingerprints.java"
    # shellcheck disable=SC2086 # one word per type
    exec java -cp "$LCM_JAR:$JAR:$OUT/fingerprints" Fingerprints $TYPES
    ;;
esac

if [ -n "$LOG" ]; then
  [ -f "$LOG" ] || die "no such log file: $LOG"
  LOG_ABS=$(cd "$(dirname "$LOG")" && pwd)/$(basename "$LOG")
  URL="file://$LOG_ABS?speed=$SPEED"
fi
case "$URL" in
  udpm://*)
    # Without a route to the group, Java LCM prints a SocketException and lcm-spy shows nothing.
    group=${URL#udpm://}
    group=${group%%[:?]*}
    if command -v ip >/dev/null 2>&1 && ! ip route get "$group" >/dev/null 2>&1; then
      die "no route to the multicast group $group, so LCM cannot open $URL. Add one (as root):" \
        "ip route add 224.0.0.0/4 dev lo (this host only; docs/clients.md §6 for a LAN)"
    fi
    ;;
esac
[ -n "${DISPLAY:-}" ] ||
  die "DISPLAY is not set: lcm-spy is a window. Without a screen: Xvfb :99 & DISPLAY=:99 $0 ..."

echo "lcm-spy.sh: lcm-spy on $URL"
# As Debian's /usr/bin/lcm-spy, without -Xincgc (removed in Java 9: the JVM refuses to start).
exec java -Djava.net.preferIPv4Stack=true -Xmx128m -Xms64m -ea \
  -cp "$LCM_JAR:$CHART_JAR:$JAR" lcm.spy.Spy --lcm-url="$URL"
