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
# --normal-maps: the screen's tangent space, OpenGL's convention, green up)
# gives its overlay Sprites that normal map in the frame `normal_frame`
# names (_normal_texture). Floors keep none: isolux does not shade the
# ground.
tool
extends Reference

var error := ""
# How normal maps are handed to Godot 3.2's Light2D, which stands its light
# `range_height` px toward the viewer over the screen's plane and reads red
# as right and green as DOWN the screen (blue ignored: z = sqrt(1 - r² - g²)):
#   "ground" (the default): re-expressed, and with the tile's height map
#       (`isolux_height_map`) a light() shader, so that the Light2D at the
#       isolux light's centre and height lights the side of each sprite
#       pixel that faces isolux's light, standing over the isometric ground;
#   "screen": the file's normal, green flipped (a light over the screen);
#   "as_written": the file's bytes.
var normal_frame := "ground"

var _map := {}            # the map element's attributes
var _props := {}          # the map's properties
var _tiles := {}          # gid -> {texture, region, offset, align}
var _floors := []         # [width, height, [gids]]
var _overlays := []       # [{gid, x, y, w, h}]
var _lights := []         # [{name, x, y, props}]
var _obstacles := []      # [{x, y, points}]
var _height_shader_made: Shader = null
var _light_textures := {}  # "WxH" -> a round light texture of that size

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
	var heights := {}  # tile id -> its height map's path
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
					if tile_id >= 0 and a.get("name", "") == "isolux_height_map" and a.get("value", "") != "":
						heights[tile_id] = base_dir.plus_file(a["value"])
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
		# The light's height over each point (normal_frame ground): only for a
		# tile that is its own image, which the height map's pixels match.
		if normal_frame == "ground" and heights.has(id):
			var t: Dictionary = _tiles[first + id]
			var hm = _height_texture(heights[id], t["texture"].get_size())
			if hm is String:
				return _fail(where, "isolux_height_map \"%s\" %s" % [heights[id], hm])
			if t["region"] == Rect2(Vector2.ZERO, t["texture"].get_size()):
				var m = ShaderMaterial.new()
				m.shader = _height_shader()
				m.set_shader_param("height_map", hm)
				t["material"] = m
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


# A normal map in `normal_frame`. For "ground": with t the file's normal
# (right, up, toward the viewer) and n = t.x R + t.y U + t.z V the same
# normal in isolux's ground frame (core/include/isolux/solid.hpp: screen
# x = X - Y, y = (X + Y) / 2 - Z; R, U, V the screen's right, up and
# toward-the-viewer unit vectors of sprite_shading.hpp), a pixel at screen
# offset (dx, dy) from where the lamp shows (y down), h - z below it, has
#   n . (light - point) = dx (nX - nY) / 2 + dy (nX + nY) + (h - z) (nX + nY + nZ)
# so g = ((nX - nY) / 2, nX + nY, nX + nY + nZ)
#      = (t.x / sqrt(2), (2 t.z - sqrt(2) t.y) / sqrt(3), sqrt(3) t.z),
# normalised, has with (dx, dy, h - z) (HEIGHT_SHADER's light()) a cosine
# of the sign of isolux's.
func _normal_texture(path: String) -> ImageTexture:
	var img = Image.new()
	if img.load(path) != OK:
		return null
	if normal_frame != "as_written":
		img.convert(Image.FORMAT_RGBA8)
		img.lock()
		for y in range(img.get_height()):
			for x in range(img.get_width()):
				var c = img.get_pixel(x, y)
				var t = Vector3(c.r * 2.0 - 1.0, c.g * 2.0 - 1.0, c.b * 2.0 - 1.0)
				var g = Vector3(t.x, -t.y, t.z)
				if normal_frame == "ground":
					g = Vector3(t.x / sqrt(2.0), (2.0 * t.z - sqrt(2.0) * t.y) / sqrt(3.0), sqrt(3.0) * t.z)
				g = g.normalized() if g.length() > 0 else Vector3(0, 0, 1)
				img.set_pixel(x, y, Color((g.x + 1.0) / 2.0, (g.y + 1.0) / 2.0, (g.z + 1.0) / 2.0, c.a))
		img.unlock()
	var tex = ImageTexture.new()
	tex.create_from_image(img, 0)
	return tex


# Godot's Light2D stands range_height over the screen's plane, at its node;
# isolux's light stands that high over its ground point, where the node is,
# and shows range_height px above it on the screen. So from each pixel the
# light() below measures the direction to the lamp as it shows (LIGHT_VEC,
# pixel minus light, moved down by the height) and its height over the point
# the pixel shows (z, the tile's height map): range_height - z. With the
# normal map re-expressed (_normal_texture), Godot's cosine then has the
# sign of isolux's. The node stands on the ground point, so Godot's shadows
# and the light's texture are placed from there. (Godot 3.2 runs a light()
# only when it writes LIGHT: it keeps its value.)
const HEIGHT_SHADER := """shader_type canvas_item;
uniform sampler2D height_map;
void light() {
	LIGHT_VEC.y += LIGHT_HEIGHT;
	LIGHT_HEIGHT -= texture(height_map, UV).r;
	LIGHT = LIGHT;
}
"""


func _height_shader() -> Shader:
	if _height_shader_made == null:
		_height_shader_made = Shader.new()
		_height_shader_made.code = HEIGHT_SHADER
	return _height_shader_made


const MAX_HEIGHT_MAP := 1048576  # pixels: decoded here in script, a few seconds at most


# An isolux height map (16-bit grey PNG, pixels above the ground) of `size`
# as a float texture, or why not (a String). Godot 3.2's own PNG loader
# narrows 16 bits to 8 through sRGB, which keeps heights only in steps of
# about 20 px, so the file is decoded here: zlib by Godot, the row filters
# below.
func _height_texture(path: String, size: Vector2):
	var f = File.new()
	if f.open(path, File.READ) != OK:
		return "cannot be read"
	var length = f.get_len()
	if length > 64 * 1048576:
		f.close()
		return "is over 64 MiB"
	var data: PoolByteArray = f.get_buffer(length)
	f.close()
	var signature = [137, 80, 78, 71, 13, 10, 26, 10]
	for i in range(8):
		if data.size() < 8 or data[i] != signature[i]:
			return "is not a PNG"
	var w = 0
	var h = 0
	var idat = PoolByteArray()
	var pos = 8
	while pos + 12 <= data.size():
		var n = (data[pos] << 24) | (data[pos + 1] << 16) | (data[pos + 2] << 8) | data[pos + 3]
		if pos + 12 + n > data.size():
			return "ends inside a chunk"
		var kind = data.subarray(pos + 4, pos + 7).get_string_from_ascii()
		if kind == "IHDR" and n >= 13:
			w = (data[pos + 8] << 24) | (data[pos + 9] << 16) | (data[pos + 10] << 8) | data[pos + 11]
			h = (data[pos + 12] << 24) | (data[pos + 13] << 16) | (data[pos + 14] << 8) | data[pos + 15]
			if data[pos + 16] != 16 or data[pos + 17] != 0 or data[pos + 20] != 0:
				return "is not 16-bit grey without interlacing"
		elif kind == "IDAT" and n > 0:
			idat.append_array(data.subarray(pos + 8, pos + 7 + n))
		elif kind == "IEND":
			break
		pos += 12 + n
	if w != int(size.x) or h != int(size.y):
		return "is %dx%d, its sprite %dx%d" % [w, h, size.x, size.y]
	if w * h > MAX_HEIGHT_MAP:
		return "has over %d pixels" % MAX_HEIGHT_MAP
	var stride = w * 2
	var raw = idat.decompress((stride + 1) * h, File.COMPRESSION_DEFLATE)
	if raw.size() != (stride + 1) * h:
		return "holds fewer rows than its height"
	var img = Image.new()
	img.create(w, h, false, Image.FORMAT_RF)
	img.lock()
	var prev = PoolByteArray()
	prev.resize(stride)
	for i in range(stride):
		prev[i] = 0
	var row = PoolByteArray()
	row.resize(stride)
	for y in range(h):
		var at = y * (stride + 1)
		var filter = raw[at]
		if filter > 4:
			img.unlock()
			return "has a row filter %d" % filter
		for i in range(stride):
			var a = row[i - 2] if i >= 2 else 0
			var b = prev[i]
			var v = raw[at + 1 + i]
			if filter == 1:
				v += a
			elif filter == 2:
				v += b
			elif filter == 3:
				v += (a + b) >> 1
			elif filter == 4:
				var c = prev[i - 2] if i >= 2 else 0
				var pa = abs(b - c)
				var pb = abs(a - c)
				var pc = abs(a + b - 2 * c)
				v += a if pa <= pb and pa <= pc else (b if pb <= pc else c)
			row[i] = v & 255
		for x in range(w):
			img.set_pixel(x, y, Color(float((row[2 * x] << 8) | row[2 * x + 1]), 0, 0))
		prev = row
		row = PoolByteArray()
		row.resize(stride)
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
	if t.has("material"):
		s.material = t["material"]
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
		# The ellipse lives in the texture, the node unscaled: Godot measures
		# a normal-mapped pixel's direction to the light in the node's frame.
		light.texture = _round_light(across / max(across, down), down / max(across, down))
		light.texture_scale = 2.0 * max(across, down) / 256.0
	light.color = _colour(props.get("color", ""), Color(1, 1, 1))
	light.energy = float(props.get("intensity", "1"))
	light.range_height = float(props.get("height", _props.get("light_height", "0")))
	light.shadow_enabled = true
	light.set_meta("isolux_area", Vector2(a, b))
	return light


func _round_light(sx := 1.0, sy := 1.0) -> ImageTexture:
	var w = max(1, int(round(256 * sx)))
	var h = max(1, int(round(256 * sy)))
	var key = "%dx%d" % [w, h]
	if _light_textures.has(key):
		return _light_textures[key]
	var img = Image.new()
	img.create(w, h, false, Image.FORMAT_RGBA8)
	img.lock()
	for y in range(h):
		for x in range(w):
			var d = Vector2((x + 0.5) / (w / 2.0) - 1.0, (y + 0.5) / (h / 2.0) - 1.0).length()
			var v = clamp(1.0 - d, 0.0, 1.0)
			img.set_pixel(x, y, Color(v, v, v, 1))
	img.unlock()
	var tex = ImageTexture.new()
	tex.create_from_image(img)
	_light_textures[key] = tex
	return tex


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
