#!/usr/bin/env bash
# Builds the MotionStyle Debian package, installs it with apt-get and runs the INSTALLED programs on
# the installed sample clips; then reports. Run as root or through sudo on a Debian 12 machine:
#
#   bash packaging/test_package.sh [--remove] [--fresh]
#
#   --remove   uninstall the package again at the end (apt-get remove motionstyle)
#   --fresh    also install it into a fresh, minimal Debian 12 system (debootstrap into a chroot,
#              needs the network: ~40 MB for the base system, ~150 MB of runtime packages) with
#              --no-install-recommends, run the CLI there and render the app once under Xvfb;
#              the chroot is deleted afterwards
#
# Environment:
#   MOTIONSTYLE_PACKAGE_BUILD_DIR   build folder (default <repo>/build/package)
#   MOTIONSTYLE_JOBS                parallel build jobs (default: all cores)
#   MOTIONSTYLE_DEBIAN_MIRROR       mirror for --fresh (default http://deb.debian.org/debian)
#
# The package is built for any x86-64 CPU (-DMOTIONSTYLE_ARCH=portable), without tests or benchmarks.
# The installed programs run from a scratch folder with MOTIONSTYLE_RESOURCES unset, so they must
# find /usr/share/motionstyle by themselves (core/common/resource_paths.h).
set -uo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${MOTIONSTYLE_PACKAGE_BUILD_DIR:-$root/build/package}"
jobs="${MOTIONSTYLE_JOBS:-$(nproc)}"
remove_after=0
fresh=0
for arg in "$@"; do
  case "$arg" in
    --remove) remove_after=1 ;;
    --fresh) fresh=1 ;;
    *) echo "usage: bash packaging/test_package.sh [--remove] [--fresh]" >&2; exit 2 ;;
  esac
done

SUDO=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "test_package: run as root or install sudo" >&2; exit 1; }
  SUDO="sudo"
fi

failures=0
results=()
pass() { results+=("PASS  $1"); echo "PASS: $1"; }
fail() { results+=("FAIL  $1"); echo "FAIL: $1"; failures=$((failures + 1)); }
step() { echo; echo "== $*"; }
die() { echo "test_package: $*" >&2; exit 1; }

# --- build ----------------------------------------------------------------------------------------
step "Dependencies"
bash "$root/packaging/install-deps.sh" || die "installing the build dependencies failed"

step "Configure and build (portable, Release) in $build"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMOTIONSTYLE_ARCH=portable \
  -DMOTIONSTYLE_BUILD_GUI=ON -DMOTIONSTYLE_BUILD_TESTS=OFF -DMOTIONSTYLE_BUILD_BENCH=OFF \
  -DMOTIONSTYLE_BUILD_FUZZ=OFF >"$build.configure.log" 2>&1 || { cat "$build.configure.log"; die "configure failed"; }
cmake --build "$build" -j"$jobs" || die "build failed"

step "cpack -G DEB"
rm -f "$build"/motionstyle_*.deb
(cd "$build" && cpack -G DEB) || die "cpack failed"
debs=("$build"/motionstyle_*.deb)
[ -f "${debs[0]}" ] || die "cpack wrote no motionstyle_*.deb in $build"
deb="${debs[0]}"

# --- the package itself ---------------------------------------------------------------------------
step "Package"
size_bytes=$(stat -c %s "$deb")
echo "file:     $deb"
echo "size:     $((size_bytes / 1024)) KiB ($size_bytes bytes), $(dpkg-deb -c "$deb" | grep -vc '/$') files"
dpkg-deb -f "$deb" Package Version Architecture Section Maintainer Installed-Size Depends Recommends
installed_kib=$(dpkg-deb -f "$deb" Installed-Size)

contents=$(dpkg-deb -c "$deb" | awk '{print $NF}')
expected=(./usr/bin/motionstyle ./usr/bin/motionstyle-cli
  ./usr/share/motionstyle/samples/cmu_131_01_walk.bvh ./usr/share/motionstyle/samples/zombie_walk.bvh
  ./usr/share/motionstyle/models/NOTICE ./usr/share/motionstyle/models/loss_network.memory
  ./usr/share/applications/motionstyle.desktop
  ./usr/share/icons/hicolor/scalable/apps/motionstyle.svg ./usr/share/icons/hicolor/256x256/apps/motionstyle.png
  ./usr/share/mime/packages/motionstyle.xml ./usr/share/man/man1/motionstyle-cli.1.gz
  ./usr/share/man/man1/motionstyle.1.gz ./usr/share/doc/motionstyle/copyright)
missing_files=()
for path in "${expected[@]}"; do grep -qxF "$path" <<<"$contents" || missing_files+=("$path"); done
if [ ${#missing_files[@]} -eq 0 ]; then pass "package holds the programs, samples, the loss network's memory, desktop entry, icons, MIME type, man pages and licences"
else fail "package lacks: ${missing_files[*]}"; fi
shipped_nets=$(grep -c '^\./usr/share/motionstyle/models/.*\.net$' <<<"$contents" || true)
echo "shipped networks in the package: $shipped_nets"

depends=$(dpkg-deb -f "$deb" Depends)
# Ceres links statically (Debian's CMake package imports libceres.a); its own runtime libraries
# (glog, SuiteSparse, LAPACK) come in through shlibdeps like the rest.
for library in libqt6widgets6 libqt6opengl6 libvtk9.1 libcholmod3 libgoogle-glog0v6; do
  grep -q "\b$library\b" <<<"$depends" && pass "Depends names $library" || fail "Depends lacks $library"
done

# --- install ----------------------------------------------------------------------------------------
step "apt-get install $deb"
if $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y --reinstall "$deb"; then
  pass "apt-get install ./$(basename "$deb")"
else
  fail "apt-get install ./$(basename "$deb")"
  printf '%s\n' "${results[@]}"
  exit 1
fi

# Every shared library the installed programs load must come from a package that the Depends line
# pulls in (recursively): what a fresh Debian 12 machine would get from that apt-get install.
step "Runtime libraries against the Depends closure"
closure=$(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts --no-breaks \
  --no-replaces --no-enhances motionstyle 2>/dev/null | awk '/^[a-z0-9]/ {print $1} /Depends:/ {print $2}' |
  tr -d '<>' | sed 's/:.*//' | sort -u)
unowned=()
outside=()
for library in $(ldd /usr/bin/motionstyle /usr/bin/motionstyle-cli | awk '/=> \// {print $3}' | sort -u); do
  owner=$(dpkg -S "$(readlink -f "$library")" 2>/dev/null | head -1 | cut -d: -f1) || owner=""
  [ -n "$owner" ] || owner=$(dpkg -S "$library" 2>/dev/null | head -1 | cut -d: -f1) || owner=""
  if [ -z "$owner" ]; then unowned+=("$library")
  elif ! grep -qxF "$owner" <<<"$closure"; then outside+=("$owner ($library)"); fi
done
library_count=$(ldd /usr/bin/motionstyle /usr/bin/motionstyle-cli | awk '/=> \// {print $3}' | sort -u | wc -l)
if [ ${#unowned[@]} -eq 0 ] && [ ${#outside[@]} -eq 0 ]; then
  pass "all $library_count shared libraries come from packages the Depends line pulls in"
else
  [ ${#unowned[@]} -eq 0 ] || fail "libraries no Debian package owns: ${unowned[*]}"
  [ ${#outside[@]} -eq 0 ] || fail "libraries from packages outside the Depends closure: ${outside[*]}"
fi

# --- the installed programs ----------------------------------------------------------------------
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || die "cannot enter $work"
unset MOTIONSTYLE_RESOURCES
cli=/usr/bin/motionstyle-cli
samples=/usr/share/motionstyle/samples

# expect CODE TEXT COMMAND...: the exit code must be CODE and the output must contain TEXT.
expect() {
  local code="$1" text="$2"; shift 2
  local output status
  output=$("$@" 2>&1); status=$?
  echo "\$ $*"; echo "$output" | sed 's/^/    /' | head -40
  if [ "$status" -eq "$code" ] && grep -qF -- "$text" <<<"$output"; then pass "$* (exit $status)"
  else fail "$* (exit $status, wanted $code and '$text')"; fi
}

step "Installed motionstyle-cli"
expect 0 "motionstyle-cli" "$cli" --version
expect 0 "zombie_walk.bvh" "$cli" info "$samples/cmu_131_01_walk.bvh" "$samples/zombie_walk.bvh"
expect 0 "wrote" "$cli" convert "$samples/zombie_walk.bvh" "$work/zombie60.bvh" --fps 60
expect 0 "at 60 fps" "$cli" info "$work/zombie60.bvh"
expect 0 "resources: /usr/share/motionstyle" "$cli" models
expect 2 "no-such.bvh" "$cli" info "$work/no-such.bvh"

style_net=""
for net in /usr/share/motionstyle/models/*.net; do
  [ -f "$net" ] || continue
  name=$(basename "$net" .net)
  [ "$name" = "loss_network" ] && continue
  style_net="$name"; break
done
if [ -n "$style_net" ]; then
  step "Installed motionstyle-cli stylize --net $style_net (a shipped network, by name)"
  expect 0 "wrote" "$cli" stylize --net "$style_net" "$samples/cmu_131_01_walk.bvh" --out "$work/styled.bvh" \
    --metrics "$work/styled.json"
  expect 0 "joints" "$cli" info "$work/styled.bvh"
else
  echo "(no style network in /usr/share/motionstyle/models: stylize skipped)"
fi

step "Desktop entry"
desktop=/usr/share/applications/motionstyle.desktop
if command -v desktop-file-validate >/dev/null; then
  if desktop-file-validate "$desktop"; then pass "desktop-file-validate $desktop"; else fail "desktop-file-validate $desktop"; fi
else
  # Without desktop-file-utils: the keys the launcher needs, and what they point at.
  echo "(desktop-file-validate not installed: checking the entry's keys and targets instead)"
  problems=()
  grep -qx '\[Desktop Entry\]' "$desktop" || problems+=("no [Desktop Entry] group")
  for key in Type=Application Name= Exec= Icon= Categories=; do grep -q "^$key" "$desktop" || problems+=("no $key"); done
  exec_program=$(sed -n 's/^Exec=\([^ ]*\).*/\1/p' "$desktop")
  command -v "$exec_program" >/dev/null || problems+=("Exec program '$exec_program' not on PATH")
  icon=$(sed -n 's/^Icon=//p' "$desktop")
  ls /usr/share/icons/hicolor/*/apps/"$icon".* >/dev/null 2>&1 || problems+=("icon '$icon' not in hicolor")
  grep -q '^Categories=.*;$' "$desktop" || problems+=("Categories must end with ';'")
  mime=$(sed -n 's/^MimeType=\([^;]*\);.*/\1/p' "$desktop")
  [ -z "$mime" ] || grep -q "type=\"$mime\"" /usr/share/mime/packages/motionstyle.xml || problems+=("MIME type $mime undefined")
  if [ ${#problems[@]} -eq 0 ]; then pass "desktop entry: keys present, Exec on PATH, icon installed, MIME type defined"
  else fail "desktop entry: ${problems[*]}"; fi
fi

step "Installed motionstyle --help (no window: the offscreen platform)"
expect 0 "--screenshot" env QT_QPA_PLATFORM=offscreen /usr/bin/motionstyle --help
if command -v xvfb-run >/dev/null; then
  # The installed app on its installed demo (samples and a shipped network found under /usr/share).
  step "Installed motionstyle --demo, rendered once under Xvfb"
  expect 0 "wrote $work/demo.png" xvfb-run -a -s "-screen 0 1440x900x24" /usr/bin/motionstyle --demo --screenshot "$work/demo.png"
  cp "$work/demo.png" "$build/installed-demo-screenshot.png" 2>/dev/null &&
    echo "screenshot of the installed app: $build/installed-demo-screenshot.png"
fi
step "Man pages"
for page in motionstyle-cli motionstyle; do
  file="/usr/share/man/man1/$page.1.gz"
  if [ ! -f "$file" ]; then
    # Minimal Docker images tell dpkg to skip /usr/share/man (path-exclude in /etc/dpkg/dpkg.cfg.d).
    grep -qs 'path-exclude=/usr/share/man' /etc/dpkg/dpkg.cfg.d/* && echo "($file not installed: dpkg excludes man pages here)" ||
      fail "$file not installed"
  elif command -v man >/dev/null; then
    expect 0 "$page" man -P cat -l "$file"
  else
    expect 0 ".TH" zcat "$file"
  fi
done

# --- a fresh Debian 12 ------------------------------------------------------------------------------
fresh_test() {
  local chroot_dir="$build/debian12-root"
  local mirror="${MOTIONSTYLE_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
  step "Fresh Debian 12 in $chroot_dir"
  command -v debootstrap >/dev/null ||
    $SUDO env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq debootstrap >/dev/null ||
    { fail "installing debootstrap"; return; }
  if mountpoint -q "$chroot_dir/proc"; then $SUDO umount "$chroot_dir/proc" || { fail "umount $chroot_dir/proc"; return; }; fi
  $SUDO rm -rf "$chroot_dir"
  if ! $SUDO debootstrap --variant=minbase bookworm "$chroot_dir" "$mirror" >"$build/debootstrap.log" 2>&1; then
    tail -5 "$build/debootstrap.log"; fail "debootstrap bookworm (see $build/debootstrap.log)"; return
  fi
  pass "debootstrap --variant=minbase bookworm"
  # /proc: the installed programs find /usr/share/motionstyle through /proc/self/exe.
  $SUDO mount -t proc proc "$chroot_dir/proc" || { fail "mount proc in the chroot"; return; }
  $SUDO cp /etc/resolv.conf "$chroot_dir/etc/resolv.conf"
  $SUDO cp "$deb" "$chroot_dir/tmp/"
  local in_root=($SUDO chroot "$chroot_dir" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root DEBIAN_FRONTEND=noninteractive)
  local log="$build/fresh-install.log"
  if "${in_root[@]}" apt-get update -qq >"$log" 2>&1 &&
     "${in_root[@]}" apt-get install -y --no-install-recommends "/tmp/$(basename "$deb")" >>"$log" 2>&1; then
    pass "fresh Debian 12: apt-get install --no-install-recommends ./$(basename "$deb") ($(grep -o '[0-9]* newly installed' "$log"))"
    local fresh_samples=/usr/share/motionstyle/samples
    expect 0 "resources: /usr/share/motionstyle" "${in_root[@]}" motionstyle-cli models
    expect 0 "at 60 fps" "${in_root[@]}" motionstyle-cli convert "$fresh_samples/zombie_walk.bvh" /tmp/zombie60.bvh --fps 60
    expect 0 "bone error" "${in_root[@]}" motionstyle-cli cleanup "$fresh_samples/zombie_walk.bvh" --out /tmp/clean.bvh
    [ -z "$style_net" ] || expect 0 "wrote" "${in_root[@]}" motionstyle-cli stylize --net "$style_net" \
      "$fresh_samples/cmu_131_01_walk.bvh" --out /tmp/styled.bvh
    # Xvfb is a test tool, not a dependency: the app itself must render with what Depends brought.
    if "${in_root[@]}" apt-get install -y -qq --no-install-recommends xvfb xauth >>"$log" 2>&1; then
      expect 0 "wrote /tmp/shot.png" "${in_root[@]}" xvfb-run -a -s "-screen 0 1440x900x24" motionstyle \
        --screenshot /tmp/shot.png "$fresh_samples/zombie_walk.bvh" "$fresh_samples/cmu_131_01_walk.bvh"
      $SUDO cp "$chroot_dir/tmp/shot.png" "$build/fresh-debian12-screenshot.png" 2>/dev/null &&
        echo "screenshot of the app in the fresh system: $build/fresh-debian12-screenshot.png"
    else
      fail "installing xvfb in the chroot (see $log)"
    fi
  else
    tail -20 "$log"; fail "fresh Debian 12: apt-get install ./$(basename "$deb") (see $log)"
  fi
  $SUDO umount "$chroot_dir/proc" && $SUDO rm -rf "$chroot_dir"
}
[ "$fresh" -eq 0 ] || fresh_test

if [ "$remove_after" -eq 1 ]; then
  step "apt-get remove motionstyle"
  $SUDO env DEBIAN_FRONTEND=noninteractive apt-get remove -y motionstyle >/dev/null && pass "apt-get remove motionstyle" ||
    fail "apt-get remove motionstyle"
fi

# --- report -----------------------------------------------------------------------------------------
step "Report"
echo "package:  $(basename "$deb"), $((size_bytes / 1024)) KiB, installed size $installed_kib KiB"
echo "Depends:  $depends"
printf '%s\n' "${results[@]}"
echo
if [ "$failures" -eq 0 ]; then echo "test_package: all ${#results[@]} checks passed"
else echo "test_package: $failures of ${#results[@]} checks FAILED"; fi
exit $((failures > 0))
