# Turns a Tiled map exported by isolux (isometric, CSV floors, image-collection
# or sheet tilesets) into a Godot 3.2 scene whose pixels are isolux's world
# pixels: an isometric TileMap for the floors, a Sprite per overlay, a Light2D
# per light, a LightOccluder2D per obstacle and a CanvasModulate for the
# ambient. Tiled's projection: a point (x, y) of an isometric map's object
# layer lands on screen at ((x - y) * tw / th / 2 + H * tw / 2, (x + y) / 2);
# isolux's `isolux_origin_x`, `isolux_origin_y` map properties move Tiled's
# screen (0, 0) to the world pixel isolux renders it at (0, 0 for other maps).
#
#   var level = preload("res://addons/isolux/tmx_importer.gd").new().import_tmx("/abs/level.tmx")
#   if level == null: push_error(importer.error)
#
# It keeps the limits of isolux's own TMX reader (core/src/formats/tiled/),
# with its messages: a map of at most 4096 tiles a side and 1,048,576 in all,
# integers and gids checked before use, a layer's CSV exactly its width x
# height gids, a sheet cut only where it has pixels, and a file that is
# malformed or ends early refused; every refusal returns null with `error`
# naming the file and the element.
#
# A tile whose properties name a `normal_map` (isolux-cli export-tiled
# --normal-maps: OpenGL's convention, green up) gives its overlay Sprites
# that normal map, its green flipped when `flip_normal_green` (Godot 3.2's 2D
# lights read green as down the screen: tests/godot/run.py checks it in
# Godot). Floors keep none: isolux does not shade the ground.
tool
extends Reference

var error := ""
var flip_normal_green := true

var _map := {}            # the map element's attributes
var _props := {}          # the map's properties
var _tiles := {}          # gid -> {texture, region, offset, align}
var _floors := []         # [width, height, [gids]]
var _overlays := []       # [{gid, x, y, w, h}]
var _lights := []         # [{name, x, y, props}]
var _obstacles := []      # [{x, y, points}]
var _light_texture: ImageTexture = null

const MAX_SIDE := 4096          # max_tiled_side
const MAX_TILES := 1048576      # a map's cells, as isolux's own maps
const MAX_AREA := 4096          # max_area: a light's a and b
const MAX_COORD := 1e9          # object coordinates


func import_tmx(path: String) -> Node2D:
	error = ""
	if not _read_map(path):
		return null
	return _build()


# ------------------------------------------------------------------ reading

func _fail(where: String, what: String) -> bool:
	if error == "":
		error = where + ": " + what
	return false


# Null (a refusal of _int_attr, _real_attr or _points), without comparing an
# int to null, which GDScript 3 refuses.
func _nil(v) -> bool:
	return typeof(v) == TYPE_NIL


# "FILE: <layer id="3" name="trees">", as isolux's reader names an element.
func _where(path: String, element: String, attrs: Dictionary) -> String:
	var w = path + ": <" + element
	if attrs.has("id"):
		w += " id=\"%s\"" % attrs["id"]
	if attrs.has("name"):
		w += " name=\"%s\"" % attrs["name"]
	return w + ">"


# An integer attribute in [lo, hi] (`fallback` when absent; null, with
# `error` set, when it is not one): checked as text, so a 64-bit or longer
# number is refused, never wrapped.
func _int_attr(path: String, element: String, attrs: Dictionary, name: String, lo: int, hi: int, fallback = null):
	if not attrs.has(name):
		if typeof(fallback) == TYPE_NIL:
			_fail(_where(path, element, attrs), "lacks " + name)
		return fallback
	var text: String = attrs[name]
	if not text.is_valid_integer() or text.length() > 11 or int(text) < lo or int(text) > hi:
		_fail(_where(path, element, attrs), "%s=\"%s\" is not an integer in [%d, %d]" % [name, text, lo, hi])
		return null
	return int(text)


# A number attribute within [-1e9, 1e9] (`fallback` when absent).
func _real_attr(path: String, element: String, attrs: Dictionary, name: String, fallback: float):
	if not attrs.has(name):
		return fallback
	var text: String = attrs[name]
	if not text.is_valid_float() or abs(float(text)) > MAX_COORD:
		_fail(_where(path, element, attrs), "%s=\"%s\" is not a number in [-1e9, 1e9]" % [name, text])
		return null
	return float(text)


func _read_map(path: String) -> bool:
	var p = XMLParser.new()
	if p.open(path) != OK:
		return _fail(path, "cannot be opened")
	var stack = []
	var group = ""
	var object = null
	var data_encoding = ""
	var layer_where = ""
	var read = p.read()
	while read == OK:
		var kind = p.get_node_type()
		if kind == XMLParser.NODE_ELEMENT:
			var name = p.get_node_name()
			var attrs = _attributes(p)
			var parent: String = stack.back() if stack.size() > 0 else ""
			var where = _where(path, name, attrs)
			match name:
				"map":
					_map = attrs
					if attrs.get("orientation", "") != "isometric":
						return _fail(path, "orientation \"%s\": the importer reads isometric maps" % attrs.get("orientation", ""))
					if attrs.get("infinite", "0") == "1":
						return _fail(path, "infinite maps are not read by this importer")
					var w = _int_attr(path, name, attrs, "width", 1, MAX_SIDE)
					var h = _int_attr(path, name, attrs, "height", 1, MAX_SIDE)
					if _nil(w) or _nil(h) or _nil(_int_attr(path, name, attrs, "tilewidth", 2, 4096)) \
							or _nil(_int_attr(path, name, attrs, "tileheight", 2, 4096)):
						return false
					if w * h > MAX_TILES:
						return _fail(where, "is %dx%d tiles: a map holds at most %d tiles" % [w, h, MAX_TILES])
				"tileset":
					if not _read_tileset(path, attrs, p):
						return false
				"layer":
					if _map.empty():
						return _fail(where, "comes before the <map>")
					var lw = _int_attr(path, name, attrs, "width", 1, MAX_SIDE, int(_map["width"]))
					var lh = _int_attr(path, name, attrs, "height", 1, MAX_SIDE, int(_map["height"]))
					if _nil(lw) or _nil(lh):
						return false
					if lw != int(_map["width"]) or lh != int(_map["height"]):
						return _fail(where, "is %dx%d, the map %sx%s" % [lw, lh, _map["width"], _map["height"]])
					_floors = [lw, lh, []]
					layer_where = where
				"data":
					if parent != "layer":
						return _fail(where, "lies outside a <layer>")
					data_encoding = attrs.get("encoding", "")
					if data_encoding != "csv":
						return _fail(path, "layer data encoding \"%s\": the importer reads csv (isolux's export)" % data_encoding)
				"objectgroup":
					group = attrs.get("name", "")
				"object":
					object = {"attrs": attrs, "props": {}, "points": null, "group": group, "where": where}
					if _nil(_real_attr(path, name, attrs, "x", 0.0)) or _nil(_real_attr(path, name, attrs, "y", 0.0)):
						return false
					if attrs.has("gid") and _nil(_int_attr(path, name, attrs, "gid", 0, 4294967295)):
						return false
				"polygon":
					if object != null:
						object["points"] = _points(attrs.get("points", ""))
						if _nil(object["points"]):
							return _fail(object["where"], "points=\"%s\" are not numbers within 1e9" % attrs.get("points", ""))
				"property":
					if parent == "properties" and stack.size() >= 2:
						var owner: String = stack[stack.size() - 2]
						if owner == "map":
							_props[attrs.get("name", "")] = attrs.get("value", "")
						elif owner == "object" and object != null:
							object["props"][attrs.get("name", "")] = attrs.get("value", "")
			if name == "tileset":
				pass  # _read_tileset consumed an embedded tileset whole, to its end
			elif p.is_empty():
				if name == "object" and not _object_done(object):
					return false
				if name == "object":
					object = null
				if name == "data" and not _data_done(layer_where):
					return false
			else:
				stack.push_back(name)
		elif kind == XMLParser.NODE_TEXT:
			if stack.size() > 0 and stack.back() == "data" and data_encoding == "csv":
				var limit = _floors[0] * _floors[1]
				for cell in p.get_node_data().split(",", false):
					var t = cell.strip_edges()
					if t == "":
						continue
					if not t.is_valid_integer() or t.length() > 10 or int(t) < 0 or int(t) > 4294967295:
						return _fail(layer_where, "CSV data holds a value that is not a gid")
					_floors[2].push_back(int(t))
					if _floors[2].size() > limit:
						return _fail(layer_where, "holds more than %d tiles, the layer is %dx%d" % [limit, _floors[0], _floors[1]])
		elif kind == XMLParser.NODE_ELEMENT_END:
			var name = p.get_node_name()
			if stack.size() > 0:
				stack.pop_back()
			if name == "object":
				if not _object_done(object):
					return false
				object = null
			elif name == "objectgroup":
				group = ""
			elif name == "data" and not _data_done(layer_where):
				return false
		read = p.read()
	if read != ERR_FILE_EOF:
		return _fail(path, "is not well-formed XML")
	if stack.size() > 0:
		return _fail(path, "ends inside <%s> (a truncated file?)" % stack.back())
	if _map.empty():
		return _fail(path, "no map element")
	return true


# A layer's data read whole: exactly its width x height gids.
func _data_done(layer_where: String) -> bool:
	var want = _floors[0] * _floors[1]
	if _floors[2].size() != want:
		return _fail(layer_where, "holds %d tiles, the layer is %dx%d" % [_floors[2].size(), _floors[0], _floors[1]])
	return true


func _object_done(object) -> bool:
	if object == null:
		return true
	var a: Dictionary = object["attrs"]
	var o = {"x": float(a.get("x", "0")), "y": float(a.get("y", "0")), "name": a.get("name", ""),
		"props": object["props"], "type": a.get("type", a.get("class", ""))}
	if a.has("gid"):
		o["gid"] = int(a["gid"])
		o["w"] = float(a.get("width", "0"))
		o["h"] = float(a.get("height", "0"))
		_overlays.push_back(o)
	elif object["group"] == "lights" or o["type"] == "light":
		# a and b as isolux reads them: numbers in [0, 4096] (0 lights nothing).
		for k in ["a", "b"]:
			var v = object["props"].get(k, null)
			if not _nil(v) and (not String(v).is_valid_float() or float(v) < 0 or float(v) > MAX_AREA):
				return _fail(object["where"], "property %s=\"%s\" is not a number in [0, %d]" % [k, v, MAX_AREA])
		_lights.push_back(o)
	elif object["points"] != null and (object["group"] == "obstacles" or o["type"] == "occluder"):
		o["points"] = object["points"]
		_obstacles.push_back(o)
	return true


func _attributes(p: XMLParser) -> Dictionary:
	var d = {}
	for i in range(p.get_attribute_count()):
		d[p.get_attribute_name(i)] = p.get_attribute_value(i)
	return d


func _points(text: String):
	var out = PoolVector2Array()
	for pair in text.split(" ", false):
		var xy = pair.split(",")
		if xy.size() != 2 or not xy[0].is_valid_float() or not xy[1].is_valid_float() \
				or abs(float(xy[0])) > MAX_COORD or abs(float(xy[1])) > MAX_COORD:
			return null
		out.push_back(Vector2(float(xy[0]), float(xy[1])))
	return out


# A tileset: external (source=) or embedded; image collections and sheets.
func _read_tileset(map_path: String, attrs: Dictionary, map_parser: XMLParser) -> bool:
	var first = _int_attr(map_path, "tileset", attrs, "firstgid", 1, 1 << 28, 1)
	if _nil(first):
		return false
	var p = map_parser
	var where = map_path
	var base_dir = map_path.get_base_dir()
	if attrs.has("source"):
		where = base_dir.plus_file(attrs["source"])
		p = XMLParser.new()
		if p.open(where) != OK:
			return _fail(where, "cannot be opened")
		base_dir = where.get_base_dir()
		attrs = {}
	elif map_parser.is_empty():
		return true
	var offset = Vector2.ZERO
	var cut = _sheet_cut(where, attrs) if not attrs.empty() else {}
	if _nil(cut):
		return false
	var tile_id = -1
	var normals := {}  # tile id -> its normal map's path
	var sheet: Texture = null
	var depth = 0
	while p.read() == OK:
		var kind = p.get_node_type()
		if kind == XMLParser.NODE_ELEMENT:
			var name = p.get_node_name()
			var a = _attributes(p)
			match name:
				"tileset":
					cut = _sheet_cut(where, a)
					if _nil(cut):
						return false
				"tileoffset":
					var ox = _int_attr(where, name, a, "x", -65536, 65536, 0)
					var oy = _int_attr(where, name, a, "y", -65536, 65536, 0)
					if _nil(ox) or _nil(oy):
						return false
					offset = Vector2(ox, oy)
				"tile":
					tile_id = _int_attr(where, name, a, "id", 0, 1 << 28)
					if _nil(tile_id):
						return false
				"property":
					if tile_id >= 0 and a.get("name", "") == "normal_map" and a.get("value", "") != "":
						normals[tile_id] = base_dir.plus_file(a["value"])
				"image":
					var tex = _texture(base_dir.plus_file(a.get("source", "")))
					if tex == null:
						return _fail(where, "image \"%s\" cannot be read" % a.get("source", ""))
					if tile_id >= 0:
						_tiles[first + tile_id] = {"texture": tex, "region": Rect2(Vector2.ZERO, tex.get_size())}
					else:
						sheet = tex
			if not p.is_empty():
				depth += 1
				if name == "tile":
					pass
		elif kind == XMLParser.NODE_ELEMENT_END:
			var name = p.get_node_name()
			if name == "tile":
				tile_id = -1
			if name == "tileset":
				break
			depth -= 1
	if sheet != null and not cut.empty():
		# Tiles cut row by row while they lie on the sheet, as isolux's reader
		# does: a tileset declaring millions of columns cuts what the sheet has.
		var size: Vector2 = cut["size"]
		var i = 0
		while i < cut["count"]:
			var r = Rect2(cut["margin"] + (i % cut["columns"]) * (size.x + cut["spacing"]),
				cut["margin"] + (i / cut["columns"]) * (size.y + cut["spacing"]), size.x, size.y)
			if r.end.x > sheet.get_width() or r.end.y > sheet.get_height():
				break
			_tiles[first + i] = {"texture": sheet, "region": r}
			i += 1
	for id in normals.keys():
		if not _tiles.has(first + id):
			continue
		var n = _normal_texture(normals[id])
		if n == null:
			return _fail(where, "normal_map \"%s\" cannot be read" % normals[id])
		_tiles[first + id]["normal"] = n
	for gid in _tiles.keys():
		if gid >= first and not _tiles[gid].has("offset"):
			_tiles[gid]["offset"] = offset
			_tiles[gid]["align"] = cut.get("align", "")
	return true


# A tileset element's tile size and sheet layout, each in isolux's reader's
# range (null, with `error` set, when one is not).
func _sheet_cut(path: String, a: Dictionary):
	var tw = _int_attr(path, "tileset", a, "tilewidth", 1, 65536)
	var th = _int_attr(path, "tileset", a, "tileheight", 1, 65536)
	var columns = _int_attr(path, "tileset", a, "columns", 0, 65536, 0)
	var spacing = _int_attr(path, "tileset", a, "spacing", 0, 65536, 0)
	var margin = _int_attr(path, "tileset", a, "margin", 0, 65536, 0)
	var count = _int_attr(path, "tileset", a, "tilecount", 0, 1 << 20, 1 << 20)
	for v in [tw, th, columns, spacing, margin, count]:
		if _nil(v):
			return null
	return {"size": Vector2(tw, th), "columns": max(1, columns), "spacing": spacing, "margin": margin,
		"count": count, "align": a.get("objectalignment", "")}


# Loaded straight from the file, unfiltered: Godot draws isolux's pixels.
func _texture(path: String) -> ImageTexture:
	var img = Image.new()
	if img.load(path) != OK:
		return null
	var tex = ImageTexture.new()
	tex.create_from_image(img, 0)
	return tex


# A normal map in the convention Godot 3.2's 2D lights read: green flipped
# from the file's OpenGL convention when flip_normal_green.
func _normal_texture(path: String) -> ImageTexture:
	var img = Image.new()
	if img.load(path) != OK:
		return null
	if flip_normal_green:
		img.lock()
		for y in range(img.get_height()):
			for x in range(img.get_width()):
				var c = img.get_pixel(x, y)
				c.g = 1.0 - c.g
				img.set_pixel(x, y, c)
		img.unlock()
	var tex = ImageTexture.new()
	tex.create_from_image(img, 0)
	return tex


# ------------------------------------------------------------------ building

func _tw() -> float:
	return float(_map.get("tilewidth", "0"))


func _th() -> float:
	return float(_map.get("tileheight", "0"))


func origin() -> Vector2:
	return Vector2(float(_props.get("isolux_origin_x", "0")), float(_props.get("isolux_origin_y", "0")))


# Tiled's isometric projection of an object-layer point, in world pixels.
func project(x: float, y: float) -> Vector2:
	var h = float(_map.get("height", "0"))
	return Vector2((x - y) * _tw() / _th() / 2.0 + h * _tw() / 2.0, (x + y) / 2.0) + origin()


func _build() -> Node2D:
	var root = Node2D.new()
	root.name = "Level"
	var ambient = float(_props.get("ambient_clarity", "1"))
	var modulate = CanvasModulate.new()
	modulate.name = "Ambient"
	modulate.color = Color(ambient, ambient, ambient)
	_add(root, modulate)
	_add(root, _build_floors())
	var overlays = Node2D.new()
	overlays.name = "Overlays"
	_add(root, overlays)
	for o in _overlays:
		var s = _build_sprite(o)
		if s != null:
			_add(overlays, s, root)
	var lights = Node2D.new()
	lights.name = "Lights"
	_add(root, lights)
	for l in _lights:
		_add(lights, _build_light(l), root)
	var occluders = Node2D.new()
	occluders.name = "Occluders"
	_add(root, occluders)
	for o in _obstacles:
		_add(occluders, _build_occluder(o), root)
	return root


func _add(parent: Node, child: Node, owner: Node = null) -> void:
	parent.add_child(child)
	child.owner = owner if owner != null else parent


# Floors: Tiled draws a cell's image with its bottom-left corner on the
# diamond's bottom-left (the top corner moved down by th and left by tw / 2),
# then shifted by the tileset's tileoffset. Godot draws an isometric cell's
# texture (tile origin top-left) at its top corner moved left by tw / 2,
# plus the tile's texture offset: the offset carries the rest.
func _build_floors() -> TileMap:
	var tm = TileMap.new()
	tm.name = "Floors"
	tm.mode = TileMap.MODE_ISOMETRIC
	tm.cell_size = Vector2(_tw(), _th())
	tm.cell_tile_origin = TileMap.TILE_ORIGIN_TOP_LEFT
	tm.position = project(0, 0)
	var ts = TileSet.new()
	var ids = {}
	var w: int = _floors[0] if _floors.size() > 0 else 0
	var cells: Array = _floors[2] if _floors.size() > 0 else []
	for i in range(cells.size()):
		var raw: int = cells[i]
		var gid = raw & 0x0FFFFFFF
		if gid == 0 or not _tiles.has(gid):
			continue
		if not ids.has(gid):
			var t: Dictionary = _tiles[gid]
			var id = ids.size()
			ids[gid] = id
			ts.create_tile(id)
			ts.tile_set_texture(id, t["texture"])
			ts.tile_set_region(id, t["region"])
			var size: Vector2 = t["region"].size
			ts.tile_set_texture_offset(id, Vector2(0, _th() - size.y) + t["offset"])
		tm.set_cell(i % w, i / w, ids[gid], raw & 0x80000000 != 0, raw & 0x40000000 != 0)
	tm.tile_set = ts
	return tm


# An overlay: its image aligned on its projected point as the tileset's
# objectalignment says (Tiled's default on isometric maps: bottom).
func _build_sprite(o: Dictionary):
	var raw: int = o["gid"]
	var gid = raw & 0x0FFFFFFF
	if not _tiles.has(gid):
		return null
	var t: Dictionary = _tiles[gid]
	var s = Sprite.new()
	s.texture = t["texture"]
	if t.has("normal"):
		s.normal_map = t["normal"]
	s.centered = false
	s.region_enabled = true
	s.region_rect = t["region"]
	s.flip_h = raw & 0x80000000 != 0
	s.flip_v = raw & 0x40000000 != 0
	var size: Vector2 = t["region"].size
	if o["w"] > 0 and o["h"] > 0:
		s.scale = Vector2(o["w"] / size.x, o["h"] / size.y)
		size = Vector2(o["w"], o["h"])
	var align: String = t.get("align", "")
	var at = Vector2(-size.x / 2.0, -size.y)  # bottom
	match align:
		"topleft": at = Vector2.ZERO
		"top": at = Vector2(-size.x / 2.0, 0)
		"topright": at = Vector2(-size.x, 0)
		"left": at = Vector2(0, -size.y / 2.0)
		"center": at = -size / 2.0
		"right": at = Vector2(-size.x, -size.y / 2.0)
		"bottomleft": at = Vector2(0, -size.y)
		"bottomright": at = Vector2(-size.x, -size.y)
	s.position = project(o["x"], o["y"]) + at + t["offset"]
	return s


func _colour(text: String, fallback: Color) -> Color:
	var hex = text.trim_prefix("#")
	if hex.length() == 8:
		hex = hex.substr(2)  # Tiled's #AARRGGBB
	if hex.length() != 6 or not hex.is_valid_hex_number():
		return fallback
	return Color("#" + hex)


# A light: a round texture scaled to its a x b area. With falloff_space
# ground (isolux's distances measured on the ground, dy scaled by the tile
# width over its height r), to the ellipse of ground distance inside it:
# min(a, r b) across, min(b, a / r) down.
func _build_light(l: Dictionary) -> Light2D:
	var light = Light2D.new()
	light.name = l["name"] if l["name"] != "" else "light"
	light.position = project(l["x"], l["y"])
	var props: Dictionary = l["props"]
	var a = float(props.get("a", _props.get("area_a", "128")))
	var b = float(props.get("b", _props.get("area_b", "128")))
	light.texture = _round_light()
	if min(a, b) <= 0:
		# An area of 0 lights nothing in isolux: kept, switched off, unscaled
		# (a scale of 0 would leave Godot a transform without an inverse).
		light.enabled = false
		light.texture_scale = 1.0
	else:
		var r = 1.0
		if _props.get("falloff_space", "screen") == "ground" and _th() > 0:
			r = _tw() / _th()
		var across = min(a, r * b)
		var down = min(b, a / r)
		light.texture_scale = 2.0 * max(across, down) / 256.0
		light.scale = Vector2(across / max(across, down), down / max(across, down))
	light.color = _colour(props.get("color", ""), Color(1, 1, 1))
	light.energy = float(props.get("intensity", "1"))
	light.range_height = float(props.get("height", _props.get("light_height", "0")))
	light.shadow_enabled = true
	light.set_meta("isolux_area", Vector2(a, b))
	return light


func _round_light() -> ImageTexture:
	if _light_texture != null:
		return _light_texture
	var img = Image.new()
	img.create(256, 256, false, Image.FORMAT_RGBA8)
	img.lock()
	for y in range(256):
		for x in range(256):
			var d = Vector2(x + 0.5 - 128, y + 0.5 - 128).length() / 128.0
			var v = clamp(1.0 - d, 0.0, 1.0)
			img.set_pixel(x, y, Color(v, v, v, 1))
	img.unlock()
	_light_texture = ImageTexture.new()
	_light_texture.create_from_image(img)
	return _light_texture


# An obstacle: its polygon's points projected, relative to its own point.
func _build_occluder(o: Dictionary) -> LightOccluder2D:
	var occ = LightOccluder2D.new()
	var at = project(o["x"], o["y"])
	occ.position = at
	var poly = OccluderPolygon2D.new()
	var pts = PoolVector2Array()
	for p in o["points"]:
		pts.push_back(project(o["x"] + p.x, o["y"] + p.y) - at)
	poly.polygon = pts
	occ.occluder = poly
	return occ
