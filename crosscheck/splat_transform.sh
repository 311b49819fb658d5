# Sourced by the bench scripts that run @playcanvas/splat-transform (after scripts/setup.sh):
# installs it, pinned, into the project's own tools/splat-transform, never globally, and sets
# st_version and st, its executable.
st_version=3.7.0
st_dir=$ZHF_ROOT/tools/splat-transform
if ! grep -qs "\"version\": \"$st_version\"" "$st_dir/node_modules/@playcanvas/splat-transform/package.json"; then
  echo "zhf bench: installing @playcanvas/splat-transform@$st_version into tools/splat-transform"
  mkdir -p "$st_dir"
  npm install --prefix "$st_dir" --no-audit --no-fund --loglevel=error "@playcanvas/splat-transform@$st_version" > /dev/null
fi
st=$st_dir/node_modules/.bin/splat-transform
