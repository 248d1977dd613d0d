"""build_world's stages, in the order they run, each a function of the build record (record.Build) that reads
what the stages before it left there and adds its own:

- survey.py: survey_scan (the first pass over the file: bounds, spread, the surface's extent; an unusable cloud
  stops here);
- tiling.py: plan_tiles (slabs sized by the memory budget), bin_tiles (the second pass: the tile files);
- tiles.py: build_tiles (each tile's surfaces, on Dask or in this process);
- stitching.py: stitch_tiles (the seams zipped, holes closed, folds mended: one surface, collision and visual),
  orient_surface (closed? its faces turned into the void, the water's volume checked);
- spawns.py: place_spawns (the robots' start points, clear of the walls, under the water level);
- evaluation.py: evaluate (scan-to-mesh distances, the flooded volume);
- files.py: write_meshes (the whole meshes and the parts by tile), write_worlds (the two world files);
- report.py: write_report (the report, NAME.json).
"""
