# Sourced by the set-up scripts: apt_install_or_warn, the one way they install Debian packages.
# apt_install_or_warn WHY CONSEQUENCE PACKAGE...: install Debian packages when we may
# (root with apt-get), else warn what will not work without them.
apt_install_or_warn() {
  local why=$1 consequence=$2
  shift 2
  if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
    echo "setup: installing $* $why"
    { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "$@" >/dev/null; } \
      || echo "setup: warning: could not install $*; $consequence" >&2
  else
    echo "setup: warning: missing $*; $consequence" >&2
  fi
}
