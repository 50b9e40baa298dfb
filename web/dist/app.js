var MS=Object.create;var _g=Object.defineProperty;var ES=Object.getOwnPropertyDescriptor;var wS=Object.getOwnPropertyNames;var AS=Object.getPrototypeOf,TS=Object.prototype.hasOwnProperty;var Tf=(n,e)=>()=>{try{return e||n((e={exports:{}}).exports,e),e.exports}catch(t){throw e=0,t}};var RS=(n,e,t,i)=>{if(e&&typeof e=="object"||typeof e=="function")for(let r of wS(e))!TS.call(n,r)&&r!==t&&_g(n,r,{get:()=>e[r],enumerable:!(i=ES(e,r))||i.enumerable});return n};var IS=(n,e,t)=>(t=n!=null?MS(AS(n)):{},RS(e||!n||!n.__esModule?_g(t,"default",{value:n,enumerable:!0}):t,n));var mp=Tf(Po=>{Po.hashU32=function(e){return e=e|0,e=e+2127912214+(e<<12)|0,e=e^-949894596^e>>>19,e=e+374761393+(e<<5)|0,e=e+-744332180^e<<9,e=e+-42973499+(e<<3)|0,e^-1252372727^e>>>16|0};Po.readU64=function(e,t){var i=0;return i|=e[t++]<<0,i|=e[t++]<<8,i|=e[t++]<<16,i|=e[t++]<<24,i|=e[t++]<<32,i|=e[t++]<<40,i|=e[t++]<<48,i|=e[t++]<<56,i};Po.readU32=function(e,t){var i=0;return i|=e[t++]<<0,i|=e[t++]<<8,i|=e[t++]<<16,i|=e[t++]<<24,i};Po.writeU32=function(e,t,i){e[t++]=i>>0&255,e[t++]=i>>8&255,e[t++]=i>>16&255,e[t++]=i>>24&255};Po.imul=function(e,t){var i=e>>>16,r=e&65535,s=t>>>16,o=t&65535;return r*o+(i*o+r*s<<16)|0}});var Bx=Tf(Fx=>{var mr=mp(),ks=2654435761,Vs=2246822519,Dx=3266489917,c1=668265263,Ux=374761393;function tu(n,e){return n=n|0,e=e|0,n>>>(32-e|0)|n<<e|0}function Ox(n,e,t){return n=n|0,e=e|0,t=t|0,mr.imul(n>>>(32-e|0)|n<<e,t)|0}function gp(n,e){return n=n|0,e=e|0,n>>>e^n|0}function tl(n,e,t,i,r){return Ox(mr.imul(e,t)+n,i,r)}function u1(n,e,t){return Ox(n+mr.imul(e[t],Ux),11,ks)}function h1(n,e,t){return tl(n,mr.readU32(e,t),Dx,17,c1)}function f1(n,e,t){return[tl(n[0],mr.readU32(e,t+0),Vs,13,ks),tl(n[1],mr.readU32(e,t+4),Vs,13,ks),tl(n[2],mr.readU32(e,t+8),Vs,13,ks),tl(n[3],mr.readU32(e,t+12),Vs,13,ks)]}function d1(n,e,t,i){var r,s;if(s=i,i>=16){for(r=[n+ks+Vs,n+Vs,n,n-ks];i>=16;)r=f1(r,e,t),t+=16,i-=16;r=tu(r[0],1)+tu(r[1],7)+tu(r[2],12)+tu(r[3],18)+s}else r=n+Ux+i>>>0;for(;i>=4;)r=h1(r,e,t),t+=4,i-=4;for(;i>0;)r=u1(r,e,t),t++,i--;return r=gp(mr.imul(gp(mr.imul(gp(r,15),Vs),13),Dx),16),r>>>0}Fx.hash=d1});var Zx=Tf(Fn=>{var p1=Bx(),Di=mp(),iu=4,m1=13,kx=5,yp=6,ru=65536,nl=4,nu=(1<<nl)-1,g1=4,Lo=(1<<g1)-1,Vx=Xx(5<<20),_p=_1(),vp=407708164,y1=4,zx=8,Hx=16,bp=64,xp=192,su=2147483648,Gx=7,Sp=4,Wx=7,ou={4:65536,5:262144,6:1048576,7:4194304};function _1(){try{return new Uint32Array(ru)}catch{for(var n=new Array(ru),e=0;e<ru;e++)n[e]=0;return n}}function x1(n){for(var e=0;e<ru;e++)_p[e]=0}function Xx(n){try{return new Uint8Array(n)}catch{for(var e=new Array(n),t=0;t<n;t++)e[t]=0;return e}}function Yx(n,e,t){if(typeof n.buffer!==void 0){if(Uint8Array.prototype.slice)return n.slice(e,t);var i=n.length;e=e|0,e=e<0?Math.max(i+e,0):Math.min(e,i),t=t===void 0?i:t|0,t=t<0?Math.max(i+t,0):Math.min(t,i);for(var r=new Uint8Array(t-e),s=e,o=0;s<t;)r[o++]=n[s++];return r}else return n.slice(e,t)}Fn.compressBound=function(e){return e+e/255+16|0};Fn.decompressBound=function(e){var t=0;if(Di.readU32(e,t)!==vp)throw new Error("invalid magic number");t+=4;var i=e[t++];if((i&xp)!==bp)throw new Error("incompatible descriptor version "+(i&xp));var r=(i&Hx)!==0,s=(i&zx)!==0,o=e[t++]>>Sp&Wx;if(ou[o]===void 0)throw new Error("invalid block size "+o);var a=ou[o];if(s)return Di.readU64(e,t);t++;for(var l=0;;){var c=Di.readU32(e,t);if(t+=4,c&su?(c&=~su,l+=c):l+=a,c===0)return l;r&&(t+=4),t+=c}};Fn.makeBuffer=Xx;Fn.decompressBlock=function(e,t,i,r,s){var o,a,l,c,u;for(l=i+r;i<l;){var h=e[i++],f=h>>4;if(f>0){if(f===15)for(;f+=e[i],e[i++]===255;);for(c=i+f;i<c;)t[s++]=e[i++]}if(i>=l)break;if(o=h&15,a=e[i++]|e[i++]<<8,o===15)for(;o+=e[i],e[i++]===255;);for(o+=iu,u=s-a,c=u+o;u<c;)t[s++]=t[u++]|0}return s};Fn.compressBlock=function(e,t,i,r,s){var o,a,l,c,u,h,f,d,p;if(f=0,d=r+i,a=i,r>=m1)for(var x=(1<<yp)+3;i+iu<d-kx;){var m=Di.readU32(e,i),g=Di.hashU32(m)>>>0;if(g=(g>>16^g)>>>0&65535,o=s[g]-1,s[g]=i+1,o<0||i-o>>>16>0||Di.readU32(e,o)!==m){u=x++>>yp,i+=u;continue}for(x=(1<<yp)+3,h=i-a,c=i-o,i+=iu,o+=iu,l=i;i<d-kx&&e[i]===e[o];)i++,o++;l=i-l;var v=l<nu?l:nu;if(h>=Lo){for(t[f++]=(Lo<<nl)+v,p=h-Lo;p>=255;p-=255)t[f++]=255;t[f++]=p}else t[f++]=(h<<nl)+v;for(var T=0;T<h;T++)t[f++]=e[a+T];if(t[f++]=c,t[f++]=c>>8,l>=nu){for(p=l-nu;p>=255;p-=255)t[f++]=255;t[f++]=p}a=i}if(a===0)return 0;if(h=d-a,h>=Lo){for(t[f++]=Lo<<nl,p=h-Lo;p>=255;p-=255)t[f++]=255;t[f++]=p}else t[f++]=h<<nl;for(i=a;i<d;)t[f++]=e[i++];return f};Fn.decompressFrame=function(e,t){var i,r,s,o,a=0,l=0;if(Di.readU32(e,a)!==vp)throw new Error("invalid magic number");if(a+=4,o=e[a++],(o&xp)!==bp)throw new Error("incompatible descriptor version");i=(o&Hx)!==0,r=(o&y1)!==0,s=(o&zx)!==0;var c=e[a++]>>Sp&Wx;if(ou[c]===void 0)throw new Error("invalid block size");for(s&&(a+=8),a++;;){var u;if(u=Di.readU32(e,a),a+=4,u===0)break;if(i&&(a+=4),(u&su)!==0){u&=~su;for(var h=0;h<u;h++)t[l++]=e[a++]}else l=Fn.decompressBlock(e,t,a,u,l),a+=u}return r&&(a+=4),l};Fn.compressFrame=function(e,t){var i=0;Di.writeU32(t,i,vp),i+=4,t[i++]=bp,t[i++]=Gx<<Sp,t[i]=p1.hash(0,t,4,i-4)>>8,i++;var r=ou[Gx],s=e.length,o=0;for(x1(_p);s>0;){var a=0,l=s>r?r:s;if(a=Fn.compressBlock(e,Vx,o,l,_p),a>l||a===0){Di.writeU32(t,i,2147483648|l),i+=4;for(var c=o+l;o<c;)t[i++]=e[o++];s-=l}else{Di.writeU32(t,i,a),i+=4;for(var u=0;u<a;)t[i++]=Vx[u++];o+=l,s-=l}}return Di.writeU32(t,i,0),i+=4,i};Fn.decompress=function(e,t){var i,r;return t===void 0&&(t=Fn.decompressBound(e)),i=Fn.makeBuffer(t),r=Fn.decompressFrame(e,i),r!==t&&(i=Yx(i,0,r)),i};Fn.compress=function(e,t){var i,r;return t===void 0&&(t=Fn.compressBound(e.length)),i=Fn.makeBuffer(t),r=Fn.compressFrame(e,i),r!==t&&(i=Yx(i,0,r)),i}});var Je;(function(n){n[n.Canceled=1]="Canceled",n[n.Unknown=2]="Unknown",n[n.InvalidArgument=3]="InvalidArgument",n[n.DeadlineExceeded=4]="DeadlineExceeded",n[n.NotFound=5]="NotFound",n[n.AlreadyExists=6]="AlreadyExists",n[n.PermissionDenied=7]="PermissionDenied",n[n.ResourceExhausted=8]="ResourceExhausted",n[n.FailedPrecondition=9]="FailedPrecondition",n[n.Aborted=10]="Aborted",n[n.OutOfRange=11]="OutOfRange",n[n.Unimplemented=12]="Unimplemented",n[n.Internal=13]="Internal",n[n.Unavailable=14]="Unavailable",n[n.DataLoss=15]="DataLoss",n[n.Unauthenticated=16]="Unauthenticated"})(Je||(Je={}));function Sa(n,e){return n!==null&&typeof n=="object"&&"$typeName"in n&&typeof n.$typeName=="string"?e===void 0?!0:e.typeName===n.$typeName:!1}var W;(function(n){n[n.DOUBLE=1]="DOUBLE",n[n.FLOAT=2]="FLOAT",n[n.INT64=3]="INT64",n[n.UINT64=4]="UINT64",n[n.INT32=5]="INT32",n[n.FIXED64=6]="FIXED64",n[n.FIXED32=7]="FIXED32",n[n.BOOL=8]="BOOL",n[n.STRING=9]="STRING",n[n.BYTES=12]="BYTES",n[n.UINT32=13]="UINT32",n[n.SFIXED32=15]="SFIXED32",n[n.SFIXED64=16]="SFIXED64",n[n.SINT32=17]="SINT32",n[n.SINT64=18]="SINT64"})(W||(W={}));function vg(){let n=0,e=0;for(let i=0;i<28;i+=7){let r=this.buf[this.pos++];if(n|=(r&127)<<i,(r&128)==0)return this.assertBounds(),[n,e]}let t=this.buf[this.pos++];if(n|=(t&15)<<28,e=(t&112)>>4,(t&128)==0)return this.assertBounds(),[n,e];for(let i=3;i<=31;i+=7){let r=this.buf[this.pos++];if(e|=(r&127)<<i,(r&128)==0)return this.assertBounds(),[n,e]}throw new Error("invalid varint")}function Jl(n,e,t){for(let s=0;s<28;s=s+7){let o=n>>>s,a=!(!(o>>>7)&&e==0),l=(a?o|128:o)&255;if(t.push(l),!a)return}let i=n>>>28&15|(e&7)<<4,r=e>>3!=0;if(t.push((r?i|128:i)&255),!!r){for(let s=3;s<31;s=s+7){let o=e>>>s,a=!!(o>>>7),l=(a?o|128:o)&255;if(t.push(l),!a)return}t.push(e>>>31&1)}}var ql=4294967296;function Rf(n){let e=n[0]==="-";e&&(n=n.slice(1));let t=1e6,i=0,r=0;function s(o,a){let l=Number(n.slice(o,a));r*=t,i=i*t+l,i>=ql&&(r=r+(i/ql|0),i=i%ql)}return s(-24,-18),s(-18,-12),s(-12,-6),s(-6),e?Sg(i,r):Cf(i,r)}function bg(n,e){let t=Cf(n,e),i=t.hi&2147483648;i&&(t=Sg(t.lo,t.hi));let r=If(t.lo,t.hi);return i?"-"+r:r}function If(n,e){if({lo:n,hi:e}=CS(n,e),e<=2097151)return String(ql*e+n);let t=n&16777215,i=(n>>>24|e<<8)&16777215,r=e>>16&65535,s=t+i*6777216+r*6710656,o=i+r*8147497,a=r*2,l=1e7;return s>=l&&(o+=Math.floor(s/l),s%=l),o>=l&&(a+=Math.floor(o/l),o%=l),a.toString()+xg(o)+xg(s)}function CS(n,e){return{lo:n>>>0,hi:e>>>0}}function Cf(n,e){return{lo:n|0,hi:e|0}}function Sg(n,e){return e=~e,n?n=~n+1:e+=1,Cf(n,e)}var xg=n=>{let e=String(n);return"0000000".slice(e.length)+e};function Ma(n,e){if(n>=0){for(;n>127;)e.push(n&127|128),n=n>>>7;e.push(n)}else{for(let t=0;t<9;t++)e.push(n&127|128),n=n>>7;e.push(1)}}function Mg(){let n=this.buf[this.pos++],e=n&127;if((n&128)==0)return this.assertBounds(),e;if(n=this.buf[this.pos++],e|=(n&127)<<7,(n&128)==0)return this.assertBounds(),e;if(n=this.buf[this.pos++],e|=(n&127)<<14,(n&128)==0)return this.assertBounds(),e;if(n=this.buf[this.pos++],e|=(n&127)<<21,(n&128)==0)return this.assertBounds(),e;n=this.buf[this.pos++],e|=(n&15)<<28;for(let t=5;(n&128)!==0&&t<10;t++)n=this.buf[this.pos++];if((n&128)!=0)throw new Error("invalid varint");return this.assertBounds(),e>>>0}var Rt=NS();function NS(){let n=new DataView(new ArrayBuffer(8));if(typeof BigInt=="function"&&typeof n.getBigInt64=="function"&&typeof n.getBigUint64=="function"&&typeof n.setBigInt64=="function"&&typeof n.setBigUint64=="function"&&(!!globalThis.Deno||!!globalThis.Bun||typeof process!="object"||typeof process.env!="object"||process.env.BUF_BIGINT_DISABLE!=="1")){let t=BigInt("-9223372036854775808"),i=BigInt("9223372036854775807"),r=BigInt("0"),s=BigInt("18446744073709551615");return{zero:BigInt(0),supported:!0,parse(o){let a=typeof o=="bigint"?o:BigInt(o);if(a>i||a<t)throw new Error(`invalid int64: ${o}`);return a},uParse(o){let a=typeof o=="bigint"?o:BigInt(o);if(a>s||a<r)throw new Error(`invalid uint64: ${o}`);return a},enc(o){return n.setBigInt64(0,this.parse(o),!0),{lo:n.getInt32(0,!0),hi:n.getInt32(4,!0)}},uEnc(o){return n.setBigInt64(0,this.uParse(o),!0),{lo:n.getInt32(0,!0),hi:n.getInt32(4,!0)}},dec(o,a){return n.setInt32(0,o,!0),n.setInt32(4,a,!0),n.getBigInt64(0,!0)},uDec(o,a){return n.setInt32(0,o,!0),n.setInt32(4,a,!0),n.getBigUint64(0,!0)}}}return{zero:"0",supported:!1,parse(t){return typeof t!="string"&&(t=t.toString()),Eg(t),t},uParse(t){return typeof t!="string"&&(t=t.toString()),wg(t),t},enc(t){return typeof t!="string"&&(t=t.toString()),Eg(t),Rf(t)},uEnc(t){return typeof t!="string"&&(t=t.toString()),wg(t),Rf(t)},dec(t,i){return bg(t,i)},uDec(t,i){return If(t,i)}}}function Eg(n){if(!/^-?[0-9]+$/.test(n))throw new Error("invalid int64: "+n)}function wg(n){if(!/^[0-9]+$/.test(n))throw new Error("invalid uint64: "+n)}function Gi(n,e){switch(n){case W.STRING:return"";case W.BOOL:return!1;case W.DOUBLE:case W.FLOAT:return 0;case W.INT64:case W.UINT64:case W.SFIXED64:case W.FIXED64:case W.SINT64:return e?"0":Rt.zero;case W.BYTES:return new Uint8Array(0);default:return 0}}function Ag(n,e){switch(n){case W.BOOL:return e===!1;case W.STRING:return e==="";case W.BYTES:return e instanceof Uint8Array&&!e.byteLength;case W.DOUBLE:case W.FLOAT:return Object.is(e,0);default:return e==0}}var Tg=2,zi=Symbol.for("reflect unsafe local");function jl(n,e){let t=n[e.localName].case;return t===void 0?t:e.fields.find(i=>i.localName===t)}function Rg(n,e){let t=e.localName;if(e.oneof)return n[e.oneof.localName].case===t;if(e.presence!=Tg)return n[t]!==void 0&&Object.prototype.hasOwnProperty.call(n,t);switch(e.fieldKind){case"list":return n[t].length>0;case"map":return Object.keys(n[t]).length>0;case"scalar":return!Ag(e.scalar,n[t]);case"enum":return n[t]!==e.enum.values[0].number}throw new Error("message field with implicit presence")}function ws(n,e){return Object.prototype.hasOwnProperty.call(n,e)&&n[e]!==void 0}function Ql(n,e){if(e.oneof){let t=n[e.oneof.localName];return t.case===e.localName?t.value:void 0}return n[e.localName]}function ec(n,e,t){e.oneof?n[e.oneof.localName]={case:e.localName,value:t}:n[e.localName]=t}function Ig(n,e){let t=e.localName;if(e.oneof){let i=e.oneof.localName;n[i].case===t&&(n[i]={case:void 0})}else if(e.presence!=Tg)delete n[t];else switch(e.fieldKind){case"map":n[t]={};break;case"list":n[t]=[];break;case"enum":n[t]=e.enum.values[0].number;break;case"scalar":n[t]=Gi(e.scalar,e.longAsString);break}}function ur(n){return n!==null&&typeof n=="object"&&!Array.isArray(n)}function Ea(n,e){var t,i,r,s;if(ur(n)&&zi in n&&"add"in n&&"field"in n&&typeof n.field=="function"){if(e!==void 0){let o=e,a=n.field();return o.listKind==a.listKind&&o.scalar===a.scalar&&((t=o.message)===null||t===void 0?void 0:t.typeName)===((i=a.message)===null||i===void 0?void 0:i.typeName)&&((r=o.enum)===null||r===void 0?void 0:r.typeName)===((s=a.enum)===null||s===void 0?void 0:s.typeName)}return!0}return!1}function wa(n,e){var t,i,r,s;if(ur(n)&&zi in n&&"has"in n&&"field"in n&&typeof n.field=="function"){if(e!==void 0){let o=e,a=n.field();return o.mapKey===a.mapKey&&o.mapKind==a.mapKind&&o.scalar===a.scalar&&((t=o.message)===null||t===void 0?void 0:t.typeName)===((i=a.message)===null||i===void 0?void 0:i.typeName)&&((r=o.enum)===null||r===void 0?void 0:r.typeName)===((s=a.enum)===null||s===void 0?void 0:s.typeName)}return!0}return!1}function Aa(n,e){return ur(n)&&zi in n&&"desc"in n&&ur(n.desc)&&n.desc.kind==="message"&&(e===void 0||n.desc.typeName==e.typeName)}function Cg(n){return Ng(n.$typeName)}function Hi(n){let e=n.fields[0];return Ng(n.typeName)&&e!==void 0&&e.fieldKind=="scalar"&&e.name=="value"&&e.number==1}function tc(n){switch(n.typeName){case"google.protobuf.Any":case"google.protobuf.Timestamp":case"google.protobuf.Duration":case"google.protobuf.FieldMask":case"google.protobuf.Struct":case"google.protobuf.Value":case"google.protobuf.ListValue":return!0;default:return Hi(n)}}function Ng(n){return n.startsWith("google.protobuf.")&&["DoubleValue","FloatValue","Int64Value","UInt64Value","Int32Value","UInt32Value","BoolValue","StringValue","BytesValue"].includes(n.substring(16))}var PS=999,LS=998,nc=2;function yn(n,e){if(Sa(e,n))return e;let t=BS(n);return e!==void 0&&DS(n,t,e),t}function DS(n,e,t){for(let i of n.members){let r=t[i.localName];if(r==null)continue;let s;if(i.kind=="oneof"){let o=jl(t,i);if(!o)continue;s=o,r=Ql(t,o)}else s=i;switch(s.fieldKind){case"message":r=Pf(s,r);break;case"scalar":r=Dg(s,r);break;case"list":r=OS(s,r);break;case"map":r=US(s,r);break}ec(e,s,r)}return e}function Dg(n,e){return n.scalar==W.BYTES?Lf(e):e}function US(n,e){if(ur(e)){if(n.scalar==W.BYTES)return Pg(e,Lf);if(n.mapKind=="message")return Pg(e,t=>Pf(n,t))}return e}function OS(n,e){if(Array.isArray(e)){if(n.scalar==W.BYTES)return e.map(Lf);if(n.listKind=="message")return e.map(t=>Pf(n,t))}return e}function Pf(n,e){if(n.fieldKind=="message"&&!n.oneof&&Hi(n.message))return Dg(n.message.fields[0],e);if(ur(e)){if(n.message.typeName=="google.protobuf.Struct"&&n.parent.typeName!=="google.protobuf.Value")return e;if(!Sa(e,n.message))return yn(n.message,e)}return e}function Lf(n){return Array.isArray(n)?new Uint8Array(n):n}function Pg(n,e){let t={};for(let i of Object.entries(n))t[i[0]]=e(i[1]);return t}var FS=Symbol(),Lg=new WeakMap;function BS(n){let e;if(kS(n)){let t=Lg.get(n),i,r;if(t)({prototype:i,members:r}=t);else{i={},r=new Set;for(let s of n.members)s.kind!="oneof"&&(s.fieldKind!="scalar"&&s.fieldKind!="enum"||s.presence!=nc&&(r.add(s),i[s.localName]=Nf(s)));Lg.set(n,{prototype:i,members:r})}e=Object.create(i),e.$typeName=n.typeName;for(let s of n.members)r.has(s)||s.kind=="field"&&(s.fieldKind=="message"||(s.fieldKind=="scalar"||s.fieldKind=="enum")&&s.presence!=nc)||(e[s.localName]=Nf(s))}else{e={$typeName:n.typeName};for(let t of n.members)(t.kind=="oneof"||t.presence==nc)&&(e[t.localName]=Nf(t))}return e}function kS(n){switch(n.file.edition){case PS:return!1;case LS:return!0;default:return n.fields.some(e=>e.presence!=nc&&e.fieldKind!="message"&&!e.oneof)}}function Nf(n){if(n.kind=="oneof")return{case:void 0};if(n.fieldKind=="list")return[];if(n.fieldKind=="map")return{};if(n.fieldKind=="message")return FS;let e=n.getDefaultValue();return e!==void 0?n.fieldKind=="scalar"&&n.longAsString?e.toString():e:n.fieldKind=="scalar"?Gi(n.scalar,n.longAsString):n.enum.values[0].number}var VS=["FieldValueInvalidError","FieldListRangeError","ForeignFieldError"],_n=class extends Error{constructor(e,t,i="FieldValueInvalidError"){super(t),this.name=i,this.field=()=>e}};function Ug(n){return n instanceof Error&&VS.includes(n.name)&&"field"in n&&typeof n.field=="function"}var Df=Symbol.for("@bufbuild/protobuf/text-encoding");function Ta(){if(globalThis[Df]==null){let n=new globalThis.TextEncoder,e=new globalThis.TextDecoder,t;globalThis[Df]={encodeUtf8(i){return n.encode(i)},decodeUtf8(i,r){return r?(t===void 0&&(t=new globalThis.TextDecoder("utf-8",{fatal:!0})),t.decode(i)):e.decode(i)},checkUtf8(i){try{return encodeURIComponent(i),!0}catch{return!1}}}}return globalThis[Df]}var en;(function(n){n[n.Varint=0]="Varint",n[n.Bit64=1]="Bit64",n[n.LengthDelimited=2]="LengthDelimited",n[n.StartGroup=3]="StartGroup",n[n.EndGroup=4]="EndGroup",n[n.Bit32=5]="Bit32"})(en||(en={}));var Of=34028234663852886e22,Ff=-34028234663852886e22,Bf=4294967295,kf=2147483647,Vf=-2147483648,co=class{constructor(e=Ta().encodeUtf8){this.encodeUtf8=e,this.stack=[],this.chunks=[],this.buf=[]}finish(){this.buf.length&&(this.chunks.push(new Uint8Array(this.buf)),this.buf=[]);let e=0;for(let r=0;r<this.chunks.length;r++)e+=this.chunks[r].length;let t=new Uint8Array(e),i=0;for(let r=0;r<this.chunks.length;r++)t.set(this.chunks[r],i),i+=this.chunks[r].length;return this.chunks=[],t}fork(){return this.stack.push({chunks:this.chunks,buf:this.buf}),this.chunks=[],this.buf=[],this}join(){let e=this.finish(),t=this.stack.pop();if(!t)throw new Error("invalid state, fork stack empty");return this.chunks=t.chunks,this.buf=t.buf,this.uint32(e.byteLength),this.raw(e)}tag(e,t){return this.uint32((e<<3|t)>>>0)}raw(e){return this.buf.length&&(this.chunks.push(new Uint8Array(this.buf)),this.buf=[]),this.chunks.push(e),this}uint32(e){for(Og(e);e>127;)this.buf.push(e&127|128),e=e>>>7;return this.buf.push(e),this}int32(e){return Uf(e),Ma(e,this.buf),this}bool(e){return this.buf.push(e?1:0),this}bytes(e){return this.uint32(e.byteLength),this.raw(e)}string(e){let t=this.encodeUtf8(e);return this.uint32(t.byteLength),this.raw(t)}float(e){GS(e);let t=new Uint8Array(4);return new DataView(t.buffer).setFloat32(0,e,!0),this.raw(t)}double(e){let t=new Uint8Array(8);return new DataView(t.buffer).setFloat64(0,e,!0),this.raw(t)}fixed32(e){Og(e);let t=new Uint8Array(4);return new DataView(t.buffer).setUint32(0,e,!0),this.raw(t)}sfixed32(e){Uf(e);let t=new Uint8Array(4);return new DataView(t.buffer).setInt32(0,e,!0),this.raw(t)}sint32(e){return Uf(e),e=(e<<1^e>>31)>>>0,Ma(e,this.buf),this}sfixed64(e){let t=new Uint8Array(8),i=new DataView(t.buffer),r=Rt.enc(e);return i.setInt32(0,r.lo,!0),i.setInt32(4,r.hi,!0),this.raw(t)}fixed64(e){let t=new Uint8Array(8),i=new DataView(t.buffer),r=Rt.uEnc(e);return i.setInt32(0,r.lo,!0),i.setInt32(4,r.hi,!0),this.raw(t)}int64(e){let t=Rt.enc(e);return Jl(t.lo,t.hi,this.buf),this}sint64(e){let t=Rt.enc(e),i=t.hi>>31,r=t.lo<<1^i,s=(t.hi<<1|t.lo>>>31)^i;return Jl(r,s,this.buf),this}uint64(e){let t=Rt.uEnc(e);return Jl(t.lo,t.hi,this.buf),this}},As=class{constructor(e,t=Ta().decodeUtf8){this.decodeUtf8=t,this.varint64=vg,this.uint32=Mg,this.buf=e,this.len=e.length,this.pos=0,this.view=new DataView(e.buffer,e.byteOffset,e.byteLength)}tag(){let e=this.pos,t=this.uint32(),i=this.pos-e;if(i>5||i==5&&this.buf[this.pos-1]>15)throw new Error("illegal tag: varint overflows uint32");let r=t>>>3,s=t&7;if(r<=0||s>5)throw new Error("illegal tag: field no "+r+" wire type "+s);return[r,s]}skip(e,t,i=100){let r=this.pos;switch(e){case en.Varint:for(;this.buf[this.pos++]&128;);break;case en.Bit64:this.pos+=4;case en.Bit32:this.pos+=4;break;case en.LengthDelimited:let s=this.uint32();this.pos+=s;break;case en.StartGroup:if(i<=0)throw new Error("maximum recursion depth reached");for(;;){let[o,a]=this.tag();if(a===en.EndGroup){if(t!==void 0&&o!==t)throw new Error("invalid end group tag");break}this.skip(a,o,i-1)}break;default:throw new Error("cant skip wire type "+e)}return this.assertBounds(),this.buf.subarray(r,this.pos)}assertBounds(){if(this.pos>this.len)throw new RangeError("premature EOF")}int32(){return this.uint32()|0}sint32(){let e=this.uint32();return e>>>1^-(e&1)}int64(){return Rt.dec(...this.varint64())}uint64(){return Rt.uDec(...this.varint64())}sint64(){let[e,t]=this.varint64(),i=-(e&1);return e=(e>>>1|(t&1)<<31)^i,t=t>>>1^i,Rt.dec(e,t)}bool(){let[e,t]=this.varint64();return e!==0||t!==0}fixed32(){return this.view.getUint32((this.pos+=4)-4,!0)}sfixed32(){return this.view.getInt32((this.pos+=4)-4,!0)}fixed64(){return Rt.uDec(this.sfixed32(),this.sfixed32())}sfixed64(){return Rt.dec(this.sfixed32(),this.sfixed32())}float(){return this.view.getFloat32((this.pos+=4)-4,!0)}double(){return this.view.getFloat64((this.pos+=8)-8,!0)}bytes(){let e=this.uint32(),t=this.pos;return this.pos+=e,this.assertBounds(),this.buf.subarray(t,t+e)}string(e){return this.decodeUtf8(this.bytes(),e)}};function Uf(n){if(typeof n=="string")n=Number(n);else if(typeof n!="number")throw new Error("invalid int32: "+typeof n);if(!Number.isInteger(n)||n>kf||n<Vf)throw new Error("invalid int32: "+n)}function Og(n){if(typeof n=="string")n=Number(n);else if(typeof n!="number")throw new Error("invalid uint32: "+typeof n);if(!Number.isInteger(n)||n>Bf||n<0)throw new Error("invalid uint32: "+n)}function GS(n){if(typeof n=="string"){let e=n;if(n=Number(n),Number.isNaN(n)&&e!=="NaN")throw new Error("invalid float32: "+e)}else if(typeof n!="number")throw new Error("invalid float32: "+typeof n);if(Number.isFinite(n)&&(n>Of||n<Ff))throw new Error("invalid float32: "+n)}function Ir(n,e){let t=n.fieldKind=="list"?Ea(e,n):n.fieldKind=="map"?wa(e,n):Hf(n,e);if(t===!0)return;let i;switch(n.fieldKind){case"list":i=`expected ${kg(n)}, got ${xn(e)}`;break;case"map":i=`expected ${Vg(n)}, got ${xn(e)}`;break;default:i=ic(n,e,t)}return new _n(n,i)}function zf(n,e,t){let i=Hf(n,t);if(i!==!0)return new _n(n,`list item #${e+1}: ${ic(n,t,i)}`)}function Fg(n,e,t){let i=Gf(e,n.mapKey);if(i!==!0)return new _n(n,`invalid map key: ${ic({scalar:n.mapKey},e,i)}`);let r=Hf(n,t);if(r!==!0)return new _n(n,`map entry ${xn(e)}: ${ic(n,t,r)}`)}function Hf(n,e){return n.scalar!==void 0?Gf(e,n.scalar):n.enum!==void 0?n.enum.open?Gf(e,W.INT32):n.enum.values.some(t=>t.number===e):Aa(e,n.message)}function Gf(n,e){switch(e){case W.DOUBLE:return typeof n=="number";case W.FLOAT:return typeof n!="number"?!1:Number.isNaN(n)||!Number.isFinite(n)?!0:n>Of||n<Ff?`${n.toFixed()} out of range`:!0;case W.INT32:case W.SFIXED32:case W.SINT32:return typeof n!="number"||!Number.isInteger(n)?!1:n>kf||n<Vf?`${n.toFixed()} out of range`:!0;case W.FIXED32:case W.UINT32:return typeof n!="number"||!Number.isInteger(n)?!1:n>Bf||n<0?`${n.toFixed()} out of range`:!0;case W.BOOL:return typeof n=="boolean";case W.STRING:return typeof n!="string"?!1:Ta().checkUtf8(n)||"invalid UTF8";case W.BYTES:return n instanceof Uint8Array;case W.INT64:case W.SFIXED64:case W.SINT64:if(typeof n=="bigint"||typeof n=="number"||typeof n=="string"&&n.length>0)try{return Rt.parse(n),!0}catch{return`${n} out of range`}return!1;case W.FIXED64:case W.UINT64:if(typeof n=="bigint"||typeof n=="number"||typeof n=="string"&&n.length>0)try{return Rt.uParse(n),!0}catch{return`${n} out of range`}return!1}}function ic(n,e,t){return t=typeof t=="string"?`: ${t}`:`, got ${xn(e)}`,n.scalar!==void 0?`expected ${zS(n.scalar)}`+t:n.enum!==void 0?`expected ${n.enum.toString()}`+t:`expected ${Bg(n.message)}`+t}function xn(n){switch(typeof n){case"object":return n===null?"null":n instanceof Uint8Array?`Uint8Array(${n.length})`:Array.isArray(n)?`Array(${n.length})`:Ea(n)?kg(n.field()):wa(n)?Vg(n.field()):Aa(n)?Bg(n.desc):Sa(n)?`message ${n.$typeName}`:"object";case"string":return n.length>30?"string":`"${n.split('"').join('\\"')}"`;case"boolean":return String(n);case"number":return String(n);case"bigint":return String(n)+"n";default:return typeof n}}function Bg(n){return`ReflectMessage (${n.typeName})`}function kg(n){switch(n.listKind){case"message":return`ReflectList (${n.message.toString()})`;case"enum":return`ReflectList (${n.enum.toString()})`;case"scalar":return`ReflectList (${W[n.scalar]})`}}function Vg(n){switch(n.mapKind){case"message":return`ReflectMap (${W[n.mapKey]}, ${n.message.toString()})`;case"enum":return`ReflectMap (${W[n.mapKey]}, ${n.enum.toString()})`;case"scalar":return`ReflectMap (${W[n.mapKey]}, ${W[n.scalar]})`}}function zS(n){switch(n){case W.STRING:return"string";case W.BOOL:return"boolean";case W.INT64:case W.SINT64:case W.SFIXED64:return"bigint (int64)";case W.UINT64:case W.FIXED64:return"bigint (uint64)";case W.BYTES:return"Uint8Array";case W.DOUBLE:return"number (float64)";case W.FLOAT:return"number (float32)";case W.FIXED32:case W.UINT32:return"number (uint32)";case W.INT32:case W.SFIXED32:case W.SINT32:return"number (int32)"}}var HS=0;function Wn(n,e,t=!0){return new sc(n,e,t)}var Gg=new WeakMap,sc=class{get sortedFields(){let e=Gg.get(this.desc);if(e)return e;let t=this.desc.fields.concat().sort((i,r)=>i.number-r.number);return Gg.set(this.desc,t),t}constructor(e,t,i=!0){this.lists=new Map,this.maps=new Map,this.check=i,this.desc=e,this.message=this[zi]=t??yn(e),this.fields=e.fields,this.oneofs=e.oneofs,this.members=e.members}findNumber(e){return this._fieldsByNumber||(this._fieldsByNumber=new Map(this.desc.fields.map(t=>[t.number,t]))),this._fieldsByNumber.get(e)}oneofCase(e){return Ra(this.message,e),jl(this.message,e)}isSet(e){return Ra(this.message,e),Rg(this.message,e)}clear(e){Ra(this.message,e),Ig(this.message,e)}get(e){Ra(this.message,e);let t=Ql(this.message,e);switch(e.fieldKind){case"list":let i=this.lists.get(e);return(!i||i[zi]!==t)&&this.lists.set(e,i=new Yf(e,t,this.check)),i;case"map":let r=this.maps.get(e);return(!r||r[zi]!==t)&&this.maps.set(e,r=new Zf(e,t,this.check)),r;case"message":return $f(e,t,this.check);case"scalar":return t===void 0?Gi(e.scalar,!1):qf(e,t);case"enum":return t??e.enum.values[0].number}}set(e,t){if(Ra(this.message,e),this.check){let r=Ir(e,t);if(r)throw r}let i;e.fieldKind=="message"?i=Kf(e,t):wa(t)||Ea(t)?i=t[zi]:i=Jf(e,t),ec(this.message,e,i)}getUnknown(){return this.message.$unknown}setUnknown(e){this.message.$unknown=e}};function Ra(n,e){if(e.parent.typeName!==n.$typeName)throw new _n(e,`cannot use ${e.toString()} with message ${n.$typeName}`,"ForeignFieldError")}var Yf=class{field(){return this._field}get size(){return this._arr.length}constructor(e,t,i){this._field=e,this._arr=this[zi]=t,this.check=i}get(e){let t=this._arr[e];return t===void 0?void 0:Wf(this._field,t,this.check)}set(e,t){if(e<0||e>=this._arr.length)throw new _n(this._field,`list item #${e+1}: out of range`);if(this.check){let i=zf(this._field,e,t);if(i)throw i}this._arr[e]=zg(this._field,t)}add(e){if(this.check){let t=zf(this._field,this._arr.length,e);if(t)throw t}this._arr.push(zg(this._field,e))}clear(){this._arr.splice(0,this._arr.length)}[Symbol.iterator](){return this.values()}keys(){return this._arr.keys()}*values(){for(let e of this._arr)yield Wf(this._field,e,this.check)}*entries(){for(let e=0;e<this._arr.length;e++)yield[e,Wf(this._field,this._arr[e],this.check)]}};var Zf=class{constructor(e,t,i=!0){this.obj=this[zi]=t??{},this.check=i,this._field=e}field(){return this._field}set(e,t){if(this.check){let i=Fg(this._field,e,t);if(i)throw i}return this.obj[rc(e)]=WS(this._field,t),this}delete(e){let t=rc(e),i=Object.prototype.hasOwnProperty.call(this.obj,t);return i&&delete this.obj[t],i}clear(){for(let e of Object.keys(this.obj))delete this.obj[e]}get(e){let t=this.obj[rc(e)];return t!==void 0&&(t=Xf(this._field,t,this.check)),t}has(e){return Object.prototype.hasOwnProperty.call(this.obj,rc(e))}*keys(){for(let e of Object.keys(this.obj))yield Hg(e,this._field.mapKey)}*entries(){for(let e of Object.entries(this.obj))yield[Hg(e[0],this._field.mapKey),Xf(this._field,e[1],this.check)]}[Symbol.iterator](){return this.entries()}get size(){return Object.keys(this.obj).length}*values(){for(let e of Object.values(this.obj))yield Xf(this._field,e,this.check)}forEach(e,t){for(let i of this.entries())e.call(t,i[1],i[0],this)}};function Kf(n,e){return Aa(e)?Cg(e.message)&&!n.oneof&&n.fieldKind=="message"?e.message.value:e.desc.typeName=="google.protobuf.Struct"&&n.parent.typeName!="google.protobuf.Value"?Xg(e.message):e.message:e}function $f(n,e,t){return e!==void 0&&(Hi(n.message)&&!n.oneof&&n.fieldKind=="message"?e={$typeName:n.message.typeName,value:qf(n.message.fields[0],e)}:n.message.typeName=="google.protobuf.Struct"&&n.parent.typeName!="google.protobuf.Value"&&ur(e)&&(e=Wg(e))),new sc(n.message,e,t)}function zg(n,e){return n.listKind=="message"?Kf(n,e):Jf(n,e)}function Wf(n,e,t){return n.listKind=="message"?$f(n,e,t):qf(n,e)}function WS(n,e){return n.mapKind=="message"?Kf(n,e):Jf(n,e)}function Xf(n,e,t){return n.mapKind=="message"?$f(n,e,t):e}function rc(n){return typeof n=="string"||typeof n=="number"?n:String(n)}function Hg(n,e){switch(e){case W.STRING:return n;case W.INT32:case W.FIXED32:case W.UINT32:case W.SFIXED32:case W.SINT32:{let t=Number.parseInt(n);if(Number.isFinite(t))return t;break}case W.BOOL:switch(n){case"true":return!0;case"false":return!1}break;case W.UINT64:case W.FIXED64:try{return Rt.uParse(n)}catch{}break;default:try{return Rt.parse(n)}catch{}break}return n}function qf(n,e){switch(n.scalar){case W.INT64:case W.SFIXED64:case W.SINT64:"longAsString"in n&&n.longAsString&&typeof e=="string"&&(e=Rt.parse(e));break;case W.FIXED64:case W.UINT64:"longAsString"in n&&n.longAsString&&typeof e=="string"&&(e=Rt.uParse(e));break}return e}function Jf(n,e){switch(n.scalar){case W.INT64:case W.SFIXED64:case W.SINT64:"longAsString"in n&&n.longAsString?e=String(e):(typeof e=="string"||typeof e=="number")&&(e=Rt.parse(e));break;case W.FIXED64:case W.UINT64:"longAsString"in n&&n.longAsString?e=String(e):(typeof e=="string"||typeof e=="number")&&(e=Rt.uParse(e));break}return e}function Wg(n){let e={$typeName:"google.protobuf.Struct",fields:{}};if(ur(n))for(let[t,i]of Object.entries(n))e.fields[t]=Zg(i);return e}function Xg(n){let e={};for(let[t,i]of Object.entries(n.fields))e[t]=Yg(i);return e}function Yg(n){switch(n.kind.case){case"structValue":return Xg(n.kind.value);case"listValue":return n.kind.value.values.map(Yg);case"nullValue":case void 0:return null;default:return n.kind.value}}function Zg(n){let e={$typeName:"google.protobuf.Value",kind:{case:void 0}};switch(typeof n){case"number":e.kind={case:"numberValue",value:n};break;case"string":e.kind={case:"stringValue",value:n};break;case"boolean":e.kind={case:"boolValue",value:n};break;case"object":if(n===null)e.kind={case:"nullValue",value:HS};else if(Array.isArray(n)){let t={$typeName:"google.protobuf.ListValue",values:[]};if(Array.isArray(n))for(let i of n)t.values.push(Zg(i));e.kind={case:"listValue",value:t}}else e.kind={case:"structValue",value:Wg(n)};break}return e}function ho(n){let e=XS(),t=n.length*3/4;n[n.length-2]=="="?t-=2:n[n.length-1]=="="&&(t-=1);let i=new Uint8Array(t),r=0,s=0,o,a=0;for(let l=0;l<n.length;l++){if(o=e[n.charCodeAt(l)],o===void 0)switch(n[l]){case"=":s=0;case`
`:case"\r":case"	":case" ":continue;default:throw Error("invalid base64 string")}switch(s){case 0:a=o,s=1;break;case 1:i[r++]=a<<2|(o&48)>>4,a=o,s=2;break;case 2:i[r++]=(a&15)<<4|(o&60)>>2,a=o,s=3;break;case 3:i[r++]=(a&3)<<6|o,s=0;break}}if(s==1)throw Error("invalid base64 string");return i.subarray(0,r)}function jf(n,e="std"){let t=$g(e),i=e=="std",r="",s=0,o,a=0;for(let l=0;l<n.length;l++)switch(o=n[l],s){case 0:r+=t[o>>2],a=(o&3)<<4,s=1;break;case 1:r+=t[a|o>>4],a=(o&15)<<2,s=2;break;case 2:r+=t[a|o>>6],r+=t[o&63],s=0;break}return s&&(r+=t[a],i&&(r+="=",s==1&&(r+="="))),r}var oc,Kg,uo;function $g(n){return oc||(oc="ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/".split(""),Kg=oc.slice(0,-2).concat("-","_")),n=="url"?Kg:oc}function XS(){if(!uo){uo=[];let n=$g("std");for(let e=0;e<n.length;e++)uo[n[e].charCodeAt(0)]=e;uo[45]=n.indexOf("+"),uo[95]=n.indexOf("/")}return uo}function Cr(n){let e=!1,t=[];for(let i=0;i<n.length;i++){let r=n.charAt(i);switch(r){case"_":e=!0;break;case"0":case"1":case"2":case"3":case"4":case"5":case"6":case"7":case"8":case"9":t.push(r),e=!1;break;default:e&&(e=!1,r=r.toUpperCase()),t.push(r);break}}return t.join("")}function ac(n){return n.replace(/[A-Z]/g,e=>"_"+e.toLowerCase())}var YS=new Set(["constructor","toString","toJSON","valueOf"]);function fo(n){return YS.has(n)?n+"$":n}function Ia(n){for(let e of n.field)ws(e,"jsonName")||(e.jsonName=Cr(e.name));n.nestedType.forEach(Ia)}function qg(n,e){let t=n.values.find(i=>i.name===e);if(!t)throw new Error(`cannot parse ${n} default value: ${e}`);return t.number}function Jg(n,e){switch(n){case W.STRING:return e;case W.BYTES:{let t=ZS(e);if(t===!1)throw new Error(`cannot parse ${W[n]} default value: ${e}`);return t}case W.INT64:case W.SFIXED64:case W.SINT64:return Rt.parse(e);case W.UINT64:case W.FIXED64:return Rt.uParse(e);case W.DOUBLE:case W.FLOAT:switch(e){case"inf":return Number.POSITIVE_INFINITY;case"-inf":return Number.NEGATIVE_INFINITY;case"nan":return Number.NaN;default:return parseFloat(e)}case W.BOOL:return e==="true";case W.INT32:case W.UINT32:case W.SINT32:case W.FIXED32:case W.SFIXED32:return parseInt(e,10)}}function ZS(n){let e=[],t={tail:n,c:"",next(){return this.tail.length==0?!1:(this.c=this.tail[0],this.tail=this.tail.substring(1),!0)},take(i){if(this.tail.length>=i){let r=this.tail.substring(0,i);return this.tail=this.tail.substring(i),r}return!1}};for(;t.next();)switch(t.c){case"\\":if(t.next())switch(t.c){case"\\":e.push(t.c.charCodeAt(0));break;case"b":e.push(8);break;case"f":e.push(12);break;case"n":e.push(10);break;case"r":e.push(13);break;case"t":e.push(9);break;case"v":e.push(11);break;case"0":case"1":case"2":case"3":case"4":case"5":case"6":case"7":{let i=t.c,r=t.take(2);if(r===!1)return!1;let s=parseInt(i+r,8);if(Number.isNaN(s))return!1;e.push(s);break}case"x":{let i=t.c,r=t.take(2);if(r===!1)return!1;let s=parseInt(i+r,16);if(Number.isNaN(s))return!1;e.push(s);break}case"u":{let i=t.c,r=t.take(4);if(r===!1)return!1;let s=parseInt(i+r,16);if(Number.isNaN(s))return!1;let o=new Uint8Array(4);new DataView(o.buffer).setInt32(0,s,!0),e.push(o[0],o[1],o[2],o[3]);break}case"U":{let i=t.c,r=t.take(8);if(r===!1)return!1;let s=Rt.uEnc(i+r),o=new Uint8Array(8),a=new DataView(o.buffer);a.setInt32(0,s.lo,!0),a.setInt32(4,s.hi,!0),e.push(o[0],o[1],o[2],o[3],o[4],o[5],o[6],o[7]);break}}break;default:e.push(t.c.charCodeAt(0))}return new Uint8Array(e)}function*lc(n){switch(n.kind){case"file":for(let e of n.messages)yield e,yield*lc(e);yield*n.enums,yield*n.services,yield*n.extensions;break;case"message":for(let e of n.nestedMessages)yield e,yield*lc(e);yield*n.nestedEnums,yield*n.nestedExtensions;break}}function cc(...n){let e=KS();if(!n.length)return e;if("$typeName"in n[0]&&n[0].$typeName=="google.protobuf.FileDescriptorSet"){for(let t of n[0].file)t0(t,e);return e}if("$typeName"in n[0]){let s=function(o){let a=[];for(let l of o.dependency){if(e.getFile(l)!=null||r.has(l))continue;let c=i(l);if(!c)throw new Error(`Unable to resolve ${l}, imported by ${o.name}`);"kind"in c?e.addFile(c,!1,!0):(r.add(c.name),a.push(c))}return a.concat(...a.map(s))},t=n[0],i=n[1],r=new Set;for(let o of[t,...s(t)].reverse())t0(o,e)}else for(let t of n)for(let i of t.files)e.addFile(i);return e}function KS(){let n=new Map,e=new Map,t=new Map;return{kind:"registry",types:n,extendees:e,[Symbol.iterator](){return n.values()},get files(){return t.values()},addFile(i,r,s){if(t.set(i.proto.name,i),!r)for(let o of lc(i))this.add(o);if(s)for(let o of i.dependencies)this.addFile(o,r,s)},add(i){if(i.kind=="extension"){let r=e.get(i.extendee.typeName);r||e.set(i.extendee.typeName,r=new Map),r.set(i.number,i)}n.set(i.typeName,i)},get(i){return n.get(i)},getFile(i){return t.get(i)},getMessage(i){let r=n.get(i);return r?.kind=="message"?r:void 0},getEnum(i){let r=n.get(i);return r?.kind=="enum"?r:void 0},getExtension(i){let r=n.get(i);return r?.kind=="extension"?r:void 0},getExtensionFor(i,r){var s;return(s=e.get(i.typeName))===null||s===void 0?void 0:s.get(r)},getService(i){let r=n.get(i);return r?.kind=="service"?r:void 0}}}var $S=998,qS=999,JS=9999,jS=9,Na=10,Ca=11,QS=12,jg=14,id=3,eM=2,Qg=1,tM=0,Qf=1,e0=2,nM=3,iM=1,rM=2,sM=1,oM=2;var aM=1001,i0={998:{fieldPresence:1,enumType:2,repeatedFieldEncoding:2,utf8Validation:3,messageEncoding:1,jsonFormat:2,enforceNamingStyle:2,defaultSymbolVisibility:1},999:{fieldPresence:2,enumType:1,repeatedFieldEncoding:1,utf8Validation:2,messageEncoding:1,jsonFormat:1,enforceNamingStyle:2,defaultSymbolVisibility:1},1e3:{fieldPresence:1,enumType:1,repeatedFieldEncoding:1,utf8Validation:2,messageEncoding:1,jsonFormat:1,enforceNamingStyle:2,defaultSymbolVisibility:1},1001:{fieldPresence:1,enumType:1,repeatedFieldEncoding:1,utf8Validation:2,messageEncoding:1,jsonFormat:1,enforceNamingStyle:1,defaultSymbolVisibility:2}};function t0(n,e){var t,i;let r={kind:"file",proto:n,deprecated:(i=(t=n.options)===null||t===void 0?void 0:t.deprecated)!==null&&i!==void 0?i:!1,edition:hM(n),name:n.name.replace(/\.proto$/,""),dependencies:fM(n,e),enums:[],messages:[],extensions:[],services:[],toString(){return`file ${n.name}`}},s=new Map,o={get(a){return s.get(a)},add(a){var l;Wi(((l=a.proto.options)===null||l===void 0?void 0:l.mapEntry)===!0),s.set(a.typeName,a)}};for(let a of n.enumType)r0(a,r,void 0,e);for(let a of n.messageType)s0(a,r,void 0,e,o);for(let a of n.service)lM(a,r,e);ed(r,e);for(let a of s.values())td(a,e,o);for(let a of r.messages)td(a,e,o),ed(a,e);e.addFile(r,!0)}function ed(n,e){switch(n.kind){case"file":for(let t of n.proto.extension){let i=nd(t,n,e);n.extensions.push(i),e.add(i)}break;case"message":for(let t of n.proto.extension){let i=nd(t,n,e);n.nestedExtensions.push(i),e.add(i)}for(let t of n.nestedMessages)ed(t,e);break}}function td(n,e,t){let i=n.proto.oneofDecl.map(s=>uM(s,n)),r=new Set;for(let s of n.proto.field){let o=mM(s,i),a=nd(s,n,e,o,t);n.fields.push(a),n.field[a.localName]=a,o===void 0?n.members.push(a):(o.fields.push(a),r.has(o)||(r.add(o),n.members.push(o)))}for(let s of i.filter(o=>r.has(o)))n.oneofs.push(s);for(let s of n.nestedMessages)td(s,e,t)}function r0(n,e,t,i){var r,s,o,a,l;let c=dM(n.name,n.value),u={kind:"enum",proto:n,deprecated:(s=(r=n.options)===null||r===void 0?void 0:r.deprecated)!==null&&s!==void 0?s:!1,file:e,parent:t,open:!0,name:n.name,typeName:uc(n,t,e),value:{},values:[],sharedPrefix:c,toString(){return`enum ${this.typeName}`}};u.open=xM(u),i.add(u);for(let h of n.value){let f=h.name;u.values.push(u.value[h.number]={kind:"enum_value",proto:h,deprecated:(a=(o=h.options)===null||o===void 0?void 0:o.deprecated)!==null&&a!==void 0?a:!1,parent:u,name:f,localName:fo(c==null?f:f.substring(c.length)),number:h.number,toString(){return`enum value ${u.typeName}.${f}`}})}((l=t?.nestedEnums)!==null&&l!==void 0?l:e.enums).push(u)}function s0(n,e,t,i,r){var s,o,a,l;let c={kind:"message",proto:n,deprecated:(o=(s=n.options)===null||s===void 0?void 0:s.deprecated)!==null&&o!==void 0?o:!1,file:e,parent:t,name:n.name,typeName:uc(n,t,e),fields:[],field:{},oneofs:[],members:[],nestedEnums:[],nestedMessages:[],nestedExtensions:[],toString(){return`message ${this.typeName}`}};((a=n.options)===null||a===void 0?void 0:a.mapEntry)===!0?r.add(c):(((l=t?.nestedMessages)!==null&&l!==void 0?l:e.messages).push(c),i.add(c));for(let u of n.enumType)r0(u,e,c,i);for(let u of n.nestedType)s0(u,e,c,i,r)}function lM(n,e,t){var i,r;let s={kind:"service",proto:n,deprecated:(r=(i=n.options)===null||i===void 0?void 0:i.deprecated)!==null&&r!==void 0?r:!1,file:e,name:n.name,typeName:uc(n,void 0,e),methods:[],method:{},toString(){return`service ${this.typeName}`}};e.services.push(s),t.add(s);for(let o of n.method){let a=cM(o,s,t);s.methods.push(a),s.method[a.localName]=a}}function cM(n,e,t){var i,r,s,o;let a;n.clientStreaming&&n.serverStreaming?a="bidi_streaming":n.clientStreaming?a="client_streaming":n.serverStreaming?a="server_streaming":a="unary";let l=t.getMessage(Nr(n.inputType)),c=t.getMessage(Nr(n.outputType));Wi(l,`invalid MethodDescriptorProto: input_type ${n.inputType} not found`),Wi(c,`invalid MethodDescriptorProto: output_type ${n.inputType} not found`);let u=n.name;return{kind:"rpc",proto:n,deprecated:(r=(i=n.options)===null||i===void 0?void 0:i.deprecated)!==null&&r!==void 0?r:!1,parent:e,name:u,localName:fo(u.length?fo(u[0].toLowerCase()+u.substring(1)):u),methodKind:a,input:l,output:c,idempotency:(o=(s=n.options)===null||s===void 0?void 0:s.idempotencyLevel)!==null&&o!==void 0?o:tM,toString(){return`rpc ${e.typeName}.${u}`}}}function uM(n,e){return{kind:"oneof",proto:n,deprecated:!1,parent:e,fields:[],name:n.name,localName:fo(Cr(n.name)),toString(){return`oneof ${e.typeName}.${this.name}`}}}function nd(n,e,t,i,r){var s,o,a;let l=r===void 0,c={kind:"field",proto:n,deprecated:(o=(s=n.options)===null||s===void 0?void 0:s.deprecated)!==null&&o!==void 0?o:!1,name:n.name,number:n.number,scalar:void 0,message:void 0,enum:void 0,presence:gM(n,i,l,e),utf8Validation:vM(n,e),listKind:void 0,mapKind:void 0,mapKey:void 0,delimitedEncoding:void 0,packed:void 0,longAsString:!1,getDefaultValue:void 0};if(l){let d=e.kind=="file"?e:e.file,p=e.kind=="file"?void 0:e,x=uc(n,p,d);c.kind="extension",c.file=d,c.parent=p,c.oneof=void 0,c.typeName=x,c.jsonName=`[${x}]`,c.toString=()=>`extension ${x}`;let m=t.getMessage(Nr(n.extendee));Wi(m,`invalid FieldDescriptorProto: extendee ${n.extendee} not found`),c.extendee=m}else{let d=e;Wi(d.kind=="message"),c.parent=d,c.oneof=i,c.localName=i?Cr(n.name):fo(Cr(n.name)),c.jsonName=n.jsonName,c.toString=()=>`field ${d.typeName}.${n.name}`}let u=n.label,h=n.type,f=(a=n.options)===null||a===void 0?void 0:a.jstype;if(u===id){let d=h==Ca?r?.get(Nr(n.typeName)):void 0;if(d){c.fieldKind="map";let{key:p,value:x}=_M(d);return c.mapKey=p.scalar,c.mapKind=x.fieldKind,c.message=x.message,c.delimitedEncoding=!1,c.enum=x.enum,c.scalar=x.scalar,c}switch(c.fieldKind="list",h){case Ca:case Na:c.listKind="message",c.message=t.getMessage(Nr(n.typeName)),Wi(c.message),c.delimitedEncoding=n0(n,e);break;case jg:c.listKind="enum",c.enum=t.getEnum(Nr(n.typeName)),Wi(c.enum);break;default:c.listKind="scalar",c.scalar=h,c.longAsString=f==Qg;break}return c.packed=yM(n,e),c}switch(h){case Ca:case Na:c.fieldKind="message",c.message=t.getMessage(Nr(n.typeName)),Wi(c.message,`invalid FieldDescriptorProto: type_name ${n.typeName} not found`),c.delimitedEncoding=n0(n,e),c.getDefaultValue=()=>{};break;case jg:{let d=t.getEnum(Nr(n.typeName));Wi(d!==void 0,`invalid FieldDescriptorProto: type_name ${n.typeName} not found`),c.fieldKind="enum",c.enum=t.getEnum(Nr(n.typeName)),c.getDefaultValue=()=>ws(n,"defaultValue")?qg(d,n.defaultValue):void 0;break}default:{c.fieldKind="scalar",c.scalar=h,c.longAsString=f==Qg,c.getDefaultValue=()=>ws(n,"defaultValue")?Jg(h,n.defaultValue):void 0;break}}return c}function hM(n){switch(n.syntax){case"":case"proto2":return $S;case"proto3":return qS;case"editions":if(n.edition===JS)return aM;if(n.edition in i0)return n.edition;throw new Error(`${n.name}: unsupported edition`);default:throw new Error(`${n.name}: unsupported syntax "${n.syntax}"`)}}function fM(n,e){return n.dependency.map(t=>{let i=e.getFile(t);if(!i)throw new Error(`Cannot find ${t}, imported by ${n.name}`);return i})}function dM(n,e){let t=pM(n)+"_";for(let i of e){if(!i.name.toLowerCase().startsWith(t))return;let r=i.name.substring(t.length);if(r.length==0||/^\d/.test(r))return}return t}function pM(n){return(n.substring(0,1)+n.substring(1).replace(/[A-Z]/g,e=>"_"+e)).toLowerCase()}function uc(n,e,t){let i;return e?i=`${e.typeName}.${n.name}`:t.proto.package.length>0?i=`${t.proto.package}.${n.name}`:i=`${n.name}`,i}function Nr(n){return n.startsWith(".")?n.substring(1):n}function mM(n,e){if(!ws(n,"oneofIndex")||n.proto3Optional)return;let t=e[n.oneofIndex];return Wi(t,`invalid FieldDescriptorProto: oneof #${n.oneofIndex} for field #${n.number} not found`),t}function gM(n,e,t,i){if(n.label==eM)return nM;if(n.label==id)return e0;if(e||n.proto3Optional||t)return Qf;let r=Ts("fieldPresence",{proto:n,parent:i});return r==e0&&(n.type==Ca||n.type==Na)?Qf:r}function yM(n,e){if(n.label!=id)return!1;switch(n.type){case jS:case QS:case Na:case Ca:return!1}let t=n.options;return t&&ws(t,"packed")?t.packed:iM==Ts("repeatedFieldEncoding",{proto:n,parent:e})}function _M(n){let e=n.fields.find(i=>i.number===1),t=n.fields.find(i=>i.number===2);return Wi(e&&e.fieldKind=="scalar"&&e.scalar!=W.BYTES&&e.scalar!=W.FLOAT&&e.scalar!=W.DOUBLE&&t&&t.fieldKind!="list"&&t.fieldKind!="map"),{key:e,value:t}}function xM(n){var e;return sM==Ts("enumType",{proto:n.proto,parent:(e=n.parent)!==null&&e!==void 0?e:n.file})}function n0(n,e){return n.type==Na?!0:rM==Ts("messageEncoding",{proto:n,parent:e})}function vM(n,e){return oM==Ts("utf8Validation",{proto:n,parent:e})}function Ts(n,e){var t,i;let r=(t=e.proto.options)===null||t===void 0?void 0:t.features;if(r){let s=r[n];if(s!=0)return s}if("kind"in e){if(e.kind=="message")return Ts(n,(i=e.parent)!==null&&i!==void 0?i:e.file);let s=i0[e.edition];if(!s)throw new Error(`feature default for edition ${e.edition} not found`);return s[n]}return Ts(n,e.parent)}function Wi(n,e){if(!n)throw new Error(e)}function o0(n){let e=bM(n);return e.messageType.forEach(Ia),cc(e,()=>{}).getFile(e.name)}function bM(n){return Object.assign(Object.create({syntax:"",edition:0}),Object.assign(Object.assign({$typeName:"google.protobuf.FileDescriptorProto",dependency:[],publicDependency:[],weakDependency:[],optionDependency:[],service:[],extension:[]},n),{messageType:n.messageType.map(a0),enumType:n.enumType.map(l0)}))}function a0(n){var e,t,i,r,s,o,a,l;return Object.assign(Object.create({visibility:0}),{$typeName:"google.protobuf.DescriptorProto",name:n.name,field:(t=(e=n.field)===null||e===void 0?void 0:e.map(SM))!==null&&t!==void 0?t:[],extension:[],nestedType:(r=(i=n.nestedType)===null||i===void 0?void 0:i.map(a0))!==null&&r!==void 0?r:[],enumType:(o=(s=n.enumType)===null||s===void 0?void 0:s.map(l0))!==null&&o!==void 0?o:[],extensionRange:(l=(a=n.extensionRange)===null||a===void 0?void 0:a.map(u=>Object.assign({$typeName:"google.protobuf.DescriptorProto.ExtensionRange"},u)))!==null&&l!==void 0?l:[],oneofDecl:[],reservedRange:[],reservedName:[]})}function SM(n){return Object.assign(Object.create({label:1,typeName:"",extendee:"",defaultValue:"",oneofIndex:0,jsonName:"",proto3Optional:!1}),Object.assign(Object.assign({$typeName:"google.protobuf.FieldDescriptorProto"},n),{options:n.options?MM(n.options):void 0}))}function MM(n){var e,t,i;return Object.assign(Object.create({ctype:0,packed:!1,jstype:0,lazy:!1,unverifiedLazy:!1,deprecated:!1,weak:!1,debugRedact:!1,retention:0}),Object.assign(Object.assign({$typeName:"google.protobuf.FieldOptions"},n),{targets:(e=n.targets)!==null&&e!==void 0?e:[],editionDefaults:(i=(t=n.editionDefaults)===null||t===void 0?void 0:t.map(s=>Object.assign({$typeName:"google.protobuf.FieldOptions.EditionDefault"},s)))!==null&&i!==void 0?i:[],uninterpretedOption:[]}))}function l0(n){return Object.assign(Object.create({visibility:0}),{$typeName:"google.protobuf.EnumDescriptorProto",name:n.name,reservedName:[],reservedRange:[],value:n.value.map(t=>Object.assign({$typeName:"google.protobuf.EnumValueDescriptorProto"},t))})}function Xn(n,e,...t){return t.reduce((i,r)=>i.nestedMessages[r],n.messages[e])}var EM=o0({name:"google/protobuf/descriptor.proto",package:"google.protobuf",messageType:[{name:"FileDescriptorSet",field:[{name:"file",number:1,type:11,label:3,typeName:".google.protobuf.FileDescriptorProto"}],extensionRange:[{start:536e6,end:536000001}]},{name:"FileDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"package",number:2,type:9,label:1},{name:"dependency",number:3,type:9,label:3},{name:"public_dependency",number:10,type:5,label:3},{name:"weak_dependency",number:11,type:5,label:3},{name:"option_dependency",number:15,type:9,label:3},{name:"message_type",number:4,type:11,label:3,typeName:".google.protobuf.DescriptorProto"},{name:"enum_type",number:5,type:11,label:3,typeName:".google.protobuf.EnumDescriptorProto"},{name:"service",number:6,type:11,label:3,typeName:".google.protobuf.ServiceDescriptorProto"},{name:"extension",number:7,type:11,label:3,typeName:".google.protobuf.FieldDescriptorProto"},{name:"options",number:8,type:11,label:1,typeName:".google.protobuf.FileOptions"},{name:"source_code_info",number:9,type:11,label:1,typeName:".google.protobuf.SourceCodeInfo"},{name:"syntax",number:12,type:9,label:1},{name:"edition",number:14,type:14,label:1,typeName:".google.protobuf.Edition"}]},{name:"DescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"field",number:2,type:11,label:3,typeName:".google.protobuf.FieldDescriptorProto"},{name:"extension",number:6,type:11,label:3,typeName:".google.protobuf.FieldDescriptorProto"},{name:"nested_type",number:3,type:11,label:3,typeName:".google.protobuf.DescriptorProto"},{name:"enum_type",number:4,type:11,label:3,typeName:".google.protobuf.EnumDescriptorProto"},{name:"extension_range",number:5,type:11,label:3,typeName:".google.protobuf.DescriptorProto.ExtensionRange"},{name:"oneof_decl",number:8,type:11,label:3,typeName:".google.protobuf.OneofDescriptorProto"},{name:"options",number:7,type:11,label:1,typeName:".google.protobuf.MessageOptions"},{name:"reserved_range",number:9,type:11,label:3,typeName:".google.protobuf.DescriptorProto.ReservedRange"},{name:"reserved_name",number:10,type:9,label:3},{name:"visibility",number:11,type:14,label:1,typeName:".google.protobuf.SymbolVisibility"}],nestedType:[{name:"ExtensionRange",field:[{name:"start",number:1,type:5,label:1},{name:"end",number:2,type:5,label:1},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.ExtensionRangeOptions"}]},{name:"ReservedRange",field:[{name:"start",number:1,type:5,label:1},{name:"end",number:2,type:5,label:1}]}]},{name:"ExtensionRangeOptions",field:[{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"},{name:"declaration",number:2,type:11,label:3,typeName:".google.protobuf.ExtensionRangeOptions.Declaration",options:{retention:2}},{name:"features",number:50,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"verification",number:3,type:14,label:1,typeName:".google.protobuf.ExtensionRangeOptions.VerificationState",defaultValue:"UNVERIFIED",options:{retention:2}}],nestedType:[{name:"Declaration",field:[{name:"number",number:1,type:5,label:1},{name:"full_name",number:2,type:9,label:1},{name:"type",number:3,type:9,label:1},{name:"reserved",number:5,type:8,label:1},{name:"repeated",number:6,type:8,label:1}]}],enumType:[{name:"VerificationState",value:[{name:"DECLARATION",number:0},{name:"UNVERIFIED",number:1}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"FieldDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"number",number:3,type:5,label:1},{name:"label",number:4,type:14,label:1,typeName:".google.protobuf.FieldDescriptorProto.Label"},{name:"type",number:5,type:14,label:1,typeName:".google.protobuf.FieldDescriptorProto.Type"},{name:"type_name",number:6,type:9,label:1},{name:"extendee",number:2,type:9,label:1},{name:"default_value",number:7,type:9,label:1},{name:"oneof_index",number:9,type:5,label:1},{name:"json_name",number:10,type:9,label:1},{name:"options",number:8,type:11,label:1,typeName:".google.protobuf.FieldOptions"},{name:"proto3_optional",number:17,type:8,label:1}],enumType:[{name:"Type",value:[{name:"TYPE_DOUBLE",number:1},{name:"TYPE_FLOAT",number:2},{name:"TYPE_INT64",number:3},{name:"TYPE_UINT64",number:4},{name:"TYPE_INT32",number:5},{name:"TYPE_FIXED64",number:6},{name:"TYPE_FIXED32",number:7},{name:"TYPE_BOOL",number:8},{name:"TYPE_STRING",number:9},{name:"TYPE_GROUP",number:10},{name:"TYPE_MESSAGE",number:11},{name:"TYPE_BYTES",number:12},{name:"TYPE_UINT32",number:13},{name:"TYPE_ENUM",number:14},{name:"TYPE_SFIXED32",number:15},{name:"TYPE_SFIXED64",number:16},{name:"TYPE_SINT32",number:17},{name:"TYPE_SINT64",number:18}]},{name:"Label",value:[{name:"LABEL_OPTIONAL",number:1},{name:"LABEL_REPEATED",number:3},{name:"LABEL_REQUIRED",number:2}]}]},{name:"OneofDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"options",number:2,type:11,label:1,typeName:".google.protobuf.OneofOptions"}]},{name:"EnumDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"value",number:2,type:11,label:3,typeName:".google.protobuf.EnumValueDescriptorProto"},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.EnumOptions"},{name:"reserved_range",number:4,type:11,label:3,typeName:".google.protobuf.EnumDescriptorProto.EnumReservedRange"},{name:"reserved_name",number:5,type:9,label:3},{name:"visibility",number:6,type:14,label:1,typeName:".google.protobuf.SymbolVisibility"}],nestedType:[{name:"EnumReservedRange",field:[{name:"start",number:1,type:5,label:1},{name:"end",number:2,type:5,label:1}]}]},{name:"EnumValueDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"number",number:2,type:5,label:1},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.EnumValueOptions"}]},{name:"ServiceDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"method",number:2,type:11,label:3,typeName:".google.protobuf.MethodDescriptorProto"},{name:"options",number:3,type:11,label:1,typeName:".google.protobuf.ServiceOptions"}]},{name:"MethodDescriptorProto",field:[{name:"name",number:1,type:9,label:1},{name:"input_type",number:2,type:9,label:1},{name:"output_type",number:3,type:9,label:1},{name:"options",number:4,type:11,label:1,typeName:".google.protobuf.MethodOptions"},{name:"client_streaming",number:5,type:8,label:1,defaultValue:"false"},{name:"server_streaming",number:6,type:8,label:1,defaultValue:"false"}]},{name:"FileOptions",field:[{name:"java_package",number:1,type:9,label:1},{name:"java_outer_classname",number:8,type:9,label:1},{name:"java_multiple_files",number:10,type:8,label:1,defaultValue:"false",options:{}},{name:"java_generate_equals_and_hash",number:20,type:8,label:1,options:{deprecated:!0}},{name:"java_string_check_utf8",number:27,type:8,label:1,defaultValue:"false"},{name:"optimize_for",number:9,type:14,label:1,typeName:".google.protobuf.FileOptions.OptimizeMode",defaultValue:"SPEED"},{name:"go_package",number:11,type:9,label:1},{name:"cc_generic_services",number:16,type:8,label:1,defaultValue:"false"},{name:"java_generic_services",number:17,type:8,label:1,defaultValue:"false"},{name:"py_generic_services",number:18,type:8,label:1,defaultValue:"false"},{name:"deprecated",number:23,type:8,label:1,defaultValue:"false"},{name:"cc_enable_arenas",number:31,type:8,label:1,defaultValue:"true"},{name:"objc_class_prefix",number:36,type:9,label:1},{name:"csharp_namespace",number:37,type:9,label:1},{name:"swift_prefix",number:39,type:9,label:1},{name:"php_class_prefix",number:40,type:9,label:1},{name:"php_namespace",number:41,type:9,label:1},{name:"php_metadata_namespace",number:44,type:9,label:1},{name:"ruby_package",number:45,type:9,label:1},{name:"features",number:50,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],enumType:[{name:"OptimizeMode",value:[{name:"SPEED",number:1},{name:"CODE_SIZE",number:2},{name:"LITE_RUNTIME",number:3}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"MessageOptions",field:[{name:"message_set_wire_format",number:1,type:8,label:1,defaultValue:"false"},{name:"no_standard_descriptor_accessor",number:2,type:8,label:1,defaultValue:"false"},{name:"deprecated",number:3,type:8,label:1,defaultValue:"false"},{name:"map_entry",number:7,type:8,label:1},{name:"deprecated_legacy_json_field_conflicts",number:11,type:8,label:1,options:{deprecated:!0}},{name:"features",number:12,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"FieldOptions",field:[{name:"ctype",number:1,type:14,label:1,typeName:".google.protobuf.FieldOptions.CType",defaultValue:"STRING"},{name:"packed",number:2,type:8,label:1},{name:"jstype",number:6,type:14,label:1,typeName:".google.protobuf.FieldOptions.JSType",defaultValue:"JS_NORMAL"},{name:"lazy",number:5,type:8,label:1,defaultValue:"false"},{name:"unverified_lazy",number:15,type:8,label:1,defaultValue:"false"},{name:"deprecated",number:3,type:8,label:1,defaultValue:"false"},{name:"weak",number:10,type:8,label:1,defaultValue:"false",options:{deprecated:!0}},{name:"debug_redact",number:16,type:8,label:1,defaultValue:"false"},{name:"retention",number:17,type:14,label:1,typeName:".google.protobuf.FieldOptions.OptionRetention"},{name:"targets",number:19,type:14,label:3,typeName:".google.protobuf.FieldOptions.OptionTargetType"},{name:"edition_defaults",number:20,type:11,label:3,typeName:".google.protobuf.FieldOptions.EditionDefault"},{name:"features",number:21,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"feature_support",number:22,type:11,label:1,typeName:".google.protobuf.FieldOptions.FeatureSupport"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],nestedType:[{name:"EditionDefault",field:[{name:"edition",number:3,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"value",number:2,type:9,label:1}]},{name:"FeatureSupport",field:[{name:"edition_introduced",number:1,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"edition_deprecated",number:2,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"deprecation_warning",number:3,type:9,label:1},{name:"edition_removed",number:4,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"removal_error",number:5,type:9,label:1}]}],enumType:[{name:"CType",value:[{name:"STRING",number:0},{name:"CORD",number:1},{name:"STRING_PIECE",number:2}]},{name:"JSType",value:[{name:"JS_NORMAL",number:0},{name:"JS_STRING",number:1},{name:"JS_NUMBER",number:2}]},{name:"OptionRetention",value:[{name:"RETENTION_UNKNOWN",number:0},{name:"RETENTION_RUNTIME",number:1},{name:"RETENTION_SOURCE",number:2}]},{name:"OptionTargetType",value:[{name:"TARGET_TYPE_UNKNOWN",number:0},{name:"TARGET_TYPE_FILE",number:1},{name:"TARGET_TYPE_EXTENSION_RANGE",number:2},{name:"TARGET_TYPE_MESSAGE",number:3},{name:"TARGET_TYPE_FIELD",number:4},{name:"TARGET_TYPE_ONEOF",number:5},{name:"TARGET_TYPE_ENUM",number:6},{name:"TARGET_TYPE_ENUM_ENTRY",number:7},{name:"TARGET_TYPE_SERVICE",number:8},{name:"TARGET_TYPE_METHOD",number:9}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"OneofOptions",field:[{name:"features",number:1,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"EnumOptions",field:[{name:"allow_alias",number:2,type:8,label:1},{name:"deprecated",number:3,type:8,label:1,defaultValue:"false"},{name:"deprecated_legacy_json_field_conflicts",number:6,type:8,label:1,options:{deprecated:!0}},{name:"features",number:7,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"EnumValueOptions",field:[{name:"deprecated",number:1,type:8,label:1,defaultValue:"false"},{name:"features",number:2,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"debug_redact",number:3,type:8,label:1,defaultValue:"false"},{name:"feature_support",number:4,type:11,label:1,typeName:".google.protobuf.FieldOptions.FeatureSupport"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"ServiceOptions",field:[{name:"features",number:34,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"deprecated",number:33,type:8,label:1,defaultValue:"false"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],extensionRange:[{start:1e3,end:536870912}]},{name:"MethodOptions",field:[{name:"deprecated",number:33,type:8,label:1,defaultValue:"false"},{name:"idempotency_level",number:34,type:14,label:1,typeName:".google.protobuf.MethodOptions.IdempotencyLevel",defaultValue:"IDEMPOTENCY_UNKNOWN"},{name:"features",number:35,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"uninterpreted_option",number:999,type:11,label:3,typeName:".google.protobuf.UninterpretedOption"}],enumType:[{name:"IdempotencyLevel",value:[{name:"IDEMPOTENCY_UNKNOWN",number:0},{name:"NO_SIDE_EFFECTS",number:1},{name:"IDEMPOTENT",number:2}]}],extensionRange:[{start:1e3,end:536870912}]},{name:"UninterpretedOption",field:[{name:"name",number:2,type:11,label:3,typeName:".google.protobuf.UninterpretedOption.NamePart"},{name:"identifier_value",number:3,type:9,label:1},{name:"positive_int_value",number:4,type:4,label:1},{name:"negative_int_value",number:5,type:3,label:1},{name:"double_value",number:6,type:1,label:1},{name:"string_value",number:7,type:12,label:1},{name:"aggregate_value",number:8,type:9,label:1}],nestedType:[{name:"NamePart",field:[{name:"name_part",number:1,type:9,label:2},{name:"is_extension",number:2,type:8,label:2}]}]},{name:"FeatureSet",field:[{name:"field_presence",number:1,type:14,label:1,typeName:".google.protobuf.FeatureSet.FieldPresence",options:{retention:1,targets:[4,1],editionDefaults:[{value:"EXPLICIT",edition:900},{value:"IMPLICIT",edition:999},{value:"EXPLICIT",edition:1e3}]}},{name:"enum_type",number:2,type:14,label:1,typeName:".google.protobuf.FeatureSet.EnumType",options:{retention:1,targets:[6,1],editionDefaults:[{value:"CLOSED",edition:900},{value:"OPEN",edition:999}]}},{name:"repeated_field_encoding",number:3,type:14,label:1,typeName:".google.protobuf.FeatureSet.RepeatedFieldEncoding",options:{retention:1,targets:[4,1],editionDefaults:[{value:"EXPANDED",edition:900},{value:"PACKED",edition:999}]}},{name:"utf8_validation",number:4,type:14,label:1,typeName:".google.protobuf.FeatureSet.Utf8Validation",options:{retention:1,targets:[4,1],editionDefaults:[{value:"NONE",edition:900},{value:"VERIFY",edition:999}]}},{name:"message_encoding",number:5,type:14,label:1,typeName:".google.protobuf.FeatureSet.MessageEncoding",options:{retention:1,targets:[4,1],editionDefaults:[{value:"LENGTH_PREFIXED",edition:900}]}},{name:"json_format",number:6,type:14,label:1,typeName:".google.protobuf.FeatureSet.JsonFormat",options:{retention:1,targets:[3,6,1],editionDefaults:[{value:"LEGACY_BEST_EFFORT",edition:900},{value:"ALLOW",edition:999}]}},{name:"enforce_naming_style",number:7,type:14,label:1,typeName:".google.protobuf.FeatureSet.EnforceNamingStyle",options:{retention:2,targets:[1,2,3,4,5,6,7,8,9],editionDefaults:[{value:"STYLE_LEGACY",edition:900},{value:"STYLE2024",edition:1001}]}},{name:"default_symbol_visibility",number:8,type:14,label:1,typeName:".google.protobuf.FeatureSet.VisibilityFeature.DefaultSymbolVisibility",options:{retention:2,targets:[1],editionDefaults:[{value:"EXPORT_ALL",edition:900},{value:"EXPORT_TOP_LEVEL",edition:1001}]}}],nestedType:[{name:"VisibilityFeature",enumType:[{name:"DefaultSymbolVisibility",value:[{name:"DEFAULT_SYMBOL_VISIBILITY_UNKNOWN",number:0},{name:"EXPORT_ALL",number:1},{name:"EXPORT_TOP_LEVEL",number:2},{name:"LOCAL_ALL",number:3},{name:"STRICT",number:4}]}]}],enumType:[{name:"FieldPresence",value:[{name:"FIELD_PRESENCE_UNKNOWN",number:0},{name:"EXPLICIT",number:1},{name:"IMPLICIT",number:2},{name:"LEGACY_REQUIRED",number:3}]},{name:"EnumType",value:[{name:"ENUM_TYPE_UNKNOWN",number:0},{name:"OPEN",number:1},{name:"CLOSED",number:2}]},{name:"RepeatedFieldEncoding",value:[{name:"REPEATED_FIELD_ENCODING_UNKNOWN",number:0},{name:"PACKED",number:1},{name:"EXPANDED",number:2}]},{name:"Utf8Validation",value:[{name:"UTF8_VALIDATION_UNKNOWN",number:0},{name:"VERIFY",number:2},{name:"NONE",number:3}]},{name:"MessageEncoding",value:[{name:"MESSAGE_ENCODING_UNKNOWN",number:0},{name:"LENGTH_PREFIXED",number:1},{name:"DELIMITED",number:2}]},{name:"JsonFormat",value:[{name:"JSON_FORMAT_UNKNOWN",number:0},{name:"ALLOW",number:1},{name:"LEGACY_BEST_EFFORT",number:2}]},{name:"EnforceNamingStyle",value:[{name:"ENFORCE_NAMING_STYLE_UNKNOWN",number:0},{name:"STYLE2024",number:1},{name:"STYLE_LEGACY",number:2}]}],extensionRange:[{start:1e3,end:9995},{start:9995,end:1e4},{start:1e4,end:10001}]},{name:"FeatureSetDefaults",field:[{name:"defaults",number:1,type:11,label:3,typeName:".google.protobuf.FeatureSetDefaults.FeatureSetEditionDefault"},{name:"minimum_edition",number:4,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"maximum_edition",number:5,type:14,label:1,typeName:".google.protobuf.Edition"}],nestedType:[{name:"FeatureSetEditionDefault",field:[{name:"edition",number:3,type:14,label:1,typeName:".google.protobuf.Edition"},{name:"overridable_features",number:4,type:11,label:1,typeName:".google.protobuf.FeatureSet"},{name:"fixed_features",number:5,type:11,label:1,typeName:".google.protobuf.FeatureSet"}]}]},{name:"SourceCodeInfo",field:[{name:"location",number:1,type:11,label:3,typeName:".google.protobuf.SourceCodeInfo.Location"}],nestedType:[{name:"Location",field:[{name:"path",number:1,type:5,label:3,options:{packed:!0}},{name:"span",number:2,type:5,label:3,options:{packed:!0}},{name:"leading_comments",number:3,type:9,label:1},{name:"trailing_comments",number:4,type:9,label:1},{name:"leading_detached_comments",number:6,type:9,label:3}]}],extensionRange:[{start:536e6,end:536000001}]},{name:"GeneratedCodeInfo",field:[{name:"annotation",number:1,type:11,label:3,typeName:".google.protobuf.GeneratedCodeInfo.Annotation"}],nestedType:[{name:"Annotation",field:[{name:"path",number:1,type:5,label:3,options:{packed:!0}},{name:"source_file",number:2,type:9,label:1},{name:"begin",number:3,type:5,label:1},{name:"end",number:4,type:5,label:1},{name:"semantic",number:5,type:14,label:1,typeName:".google.protobuf.GeneratedCodeInfo.Annotation.Semantic"}],enumType:[{name:"Semantic",value:[{name:"NONE",number:0},{name:"SET",number:1},{name:"ALIAS",number:2}]}]}]}],enumType:[{name:"Edition",value:[{name:"EDITION_UNKNOWN",number:0},{name:"EDITION_LEGACY",number:900},{name:"EDITION_PROTO2",number:998},{name:"EDITION_PROTO3",number:999},{name:"EDITION_2023",number:1e3},{name:"EDITION_2024",number:1001},{name:"EDITION_UNSTABLE",number:9999},{name:"EDITION_1_TEST_ONLY",number:1},{name:"EDITION_2_TEST_ONLY",number:2},{name:"EDITION_99997_TEST_ONLY",number:99997},{name:"EDITION_99998_TEST_ONLY",number:99998},{name:"EDITION_99999_TEST_ONLY",number:99999},{name:"EDITION_MAX",number:2147483647}]},{name:"SymbolVisibility",value:[{name:"VISIBILITY_UNSET",number:0},{name:"VISIBILITY_LOCAL",number:1},{name:"VISIBILITY_EXPORT",number:2}]}]});var I0=Xn(EM,1);var c0;(function(n){n[n.DECLARATION=0]="DECLARATION",n[n.UNVERIFIED=1]="UNVERIFIED"})(c0||(c0={}));var u0;(function(n){n[n.DOUBLE=1]="DOUBLE",n[n.FLOAT=2]="FLOAT",n[n.INT64=3]="INT64",n[n.UINT64=4]="UINT64",n[n.INT32=5]="INT32",n[n.FIXED64=6]="FIXED64",n[n.FIXED32=7]="FIXED32",n[n.BOOL=8]="BOOL",n[n.STRING=9]="STRING",n[n.GROUP=10]="GROUP",n[n.MESSAGE=11]="MESSAGE",n[n.BYTES=12]="BYTES",n[n.UINT32=13]="UINT32",n[n.ENUM=14]="ENUM",n[n.SFIXED32=15]="SFIXED32",n[n.SFIXED64=16]="SFIXED64",n[n.SINT32=17]="SINT32",n[n.SINT64=18]="SINT64"})(u0||(u0={}));var h0;(function(n){n[n.OPTIONAL=1]="OPTIONAL",n[n.REPEATED=3]="REPEATED",n[n.REQUIRED=2]="REQUIRED"})(h0||(h0={}));var f0;(function(n){n[n.SPEED=1]="SPEED",n[n.CODE_SIZE=2]="CODE_SIZE",n[n.LITE_RUNTIME=3]="LITE_RUNTIME"})(f0||(f0={}));var d0;(function(n){n[n.STRING=0]="STRING",n[n.CORD=1]="CORD",n[n.STRING_PIECE=2]="STRING_PIECE"})(d0||(d0={}));var p0;(function(n){n[n.JS_NORMAL=0]="JS_NORMAL",n[n.JS_STRING=1]="JS_STRING",n[n.JS_NUMBER=2]="JS_NUMBER"})(p0||(p0={}));var m0;(function(n){n[n.RETENTION_UNKNOWN=0]="RETENTION_UNKNOWN",n[n.RETENTION_RUNTIME=1]="RETENTION_RUNTIME",n[n.RETENTION_SOURCE=2]="RETENTION_SOURCE"})(m0||(m0={}));var g0;(function(n){n[n.TARGET_TYPE_UNKNOWN=0]="TARGET_TYPE_UNKNOWN",n[n.TARGET_TYPE_FILE=1]="TARGET_TYPE_FILE",n[n.TARGET_TYPE_EXTENSION_RANGE=2]="TARGET_TYPE_EXTENSION_RANGE",n[n.TARGET_TYPE_MESSAGE=3]="TARGET_TYPE_MESSAGE",n[n.TARGET_TYPE_FIELD=4]="TARGET_TYPE_FIELD",n[n.TARGET_TYPE_ONEOF=5]="TARGET_TYPE_ONEOF",n[n.TARGET_TYPE_ENUM=6]="TARGET_TYPE_ENUM",n[n.TARGET_TYPE_ENUM_ENTRY=7]="TARGET_TYPE_ENUM_ENTRY",n[n.TARGET_TYPE_SERVICE=8]="TARGET_TYPE_SERVICE",n[n.TARGET_TYPE_METHOD=9]="TARGET_TYPE_METHOD"})(g0||(g0={}));var y0;(function(n){n[n.IDEMPOTENCY_UNKNOWN=0]="IDEMPOTENCY_UNKNOWN",n[n.NO_SIDE_EFFECTS=1]="NO_SIDE_EFFECTS",n[n.IDEMPOTENT=2]="IDEMPOTENT"})(y0||(y0={}));var _0;(function(n){n[n.DEFAULT_SYMBOL_VISIBILITY_UNKNOWN=0]="DEFAULT_SYMBOL_VISIBILITY_UNKNOWN",n[n.EXPORT_ALL=1]="EXPORT_ALL",n[n.EXPORT_TOP_LEVEL=2]="EXPORT_TOP_LEVEL",n[n.LOCAL_ALL=3]="LOCAL_ALL",n[n.STRICT=4]="STRICT"})(_0||(_0={}));var x0;(function(n){n[n.FIELD_PRESENCE_UNKNOWN=0]="FIELD_PRESENCE_UNKNOWN",n[n.EXPLICIT=1]="EXPLICIT",n[n.IMPLICIT=2]="IMPLICIT",n[n.LEGACY_REQUIRED=3]="LEGACY_REQUIRED"})(x0||(x0={}));var v0;(function(n){n[n.ENUM_TYPE_UNKNOWN=0]="ENUM_TYPE_UNKNOWN",n[n.OPEN=1]="OPEN",n[n.CLOSED=2]="CLOSED"})(v0||(v0={}));var b0;(function(n){n[n.REPEATED_FIELD_ENCODING_UNKNOWN=0]="REPEATED_FIELD_ENCODING_UNKNOWN",n[n.PACKED=1]="PACKED",n[n.EXPANDED=2]="EXPANDED"})(b0||(b0={}));var S0;(function(n){n[n.UTF8_VALIDATION_UNKNOWN=0]="UTF8_VALIDATION_UNKNOWN",n[n.VERIFY=2]="VERIFY",n[n.NONE=3]="NONE"})(S0||(S0={}));var M0;(function(n){n[n.MESSAGE_ENCODING_UNKNOWN=0]="MESSAGE_ENCODING_UNKNOWN",n[n.LENGTH_PREFIXED=1]="LENGTH_PREFIXED",n[n.DELIMITED=2]="DELIMITED"})(M0||(M0={}));var E0;(function(n){n[n.JSON_FORMAT_UNKNOWN=0]="JSON_FORMAT_UNKNOWN",n[n.ALLOW=1]="ALLOW",n[n.LEGACY_BEST_EFFORT=2]="LEGACY_BEST_EFFORT"})(E0||(E0={}));var w0;(function(n){n[n.ENFORCE_NAMING_STYLE_UNKNOWN=0]="ENFORCE_NAMING_STYLE_UNKNOWN",n[n.STYLE2024=1]="STYLE2024",n[n.STYLE_LEGACY=2]="STYLE_LEGACY"})(w0||(w0={}));var A0;(function(n){n[n.NONE=0]="NONE",n[n.SET=1]="SET",n[n.ALIAS=2]="ALIAS"})(A0||(A0={}));var T0;(function(n){n[n.EDITION_UNKNOWN=0]="EDITION_UNKNOWN",n[n.EDITION_LEGACY=900]="EDITION_LEGACY",n[n.EDITION_PROTO2=998]="EDITION_PROTO2",n[n.EDITION_PROTO3=999]="EDITION_PROTO3",n[n.EDITION_2023=1e3]="EDITION_2023",n[n.EDITION_2024=1001]="EDITION_2024",n[n.EDITION_UNSTABLE=9999]="EDITION_UNSTABLE",n[n.EDITION_1_TEST_ONLY=1]="EDITION_1_TEST_ONLY",n[n.EDITION_2_TEST_ONLY=2]="EDITION_2_TEST_ONLY",n[n.EDITION_99997_TEST_ONLY=99997]="EDITION_99997_TEST_ONLY",n[n.EDITION_99998_TEST_ONLY=99998]="EDITION_99998_TEST_ONLY",n[n.EDITION_99999_TEST_ONLY=99999]="EDITION_99999_TEST_ONLY",n[n.EDITION_MAX=2147483647]="EDITION_MAX"})(T0||(T0={}));var R0;(function(n){n[n.VISIBILITY_UNSET=0]="VISIBILITY_UNSET",n[n.VISIBILITY_LOCAL=1]="VISIBILITY_LOCAL",n[n.VISIBILITY_EXPORT=2]="VISIBILITY_EXPORT"})(R0||(R0={}));function rd(n){return Object.assign(Object.assign({readUnknownFields:!0,recursionLimit:100},n),{depth:0})}function ii(n,e,t){let i=Wn(n,void 0,!1);return C0(i,new As(e),rd(t),!1,e.byteLength),i.message}function C0(n,e,t,i,r){var s;if(++t.depth>t.recursionLimit)throw new Error(`cannot decode ${n.desc} from binary: maximum recursion depth of ${t.recursionLimit} reached`);let o=i?e.len:e.pos+r,a,l,c=(s=n.getUnknown())!==null&&s!==void 0?s:[];for(;e.pos<o&&([a,l]=e.tag(),!(i&&l==en.EndGroup));){let u=n.findNumber(a);if(!u){let h=t.recursionLimit-t.depth,f=e.skip(l,a,h);t.readUnknownFields&&c.push({no:a,wireType:l,data:f});continue}sd(n,e,u,l,t)}if(i&&(l!=en.EndGroup||a!==r))throw new Error("invalid end group tag");c.length>0&&n.setUnknown(c),t.depth--}function sd(n,e,t,i,r){var s;switch(t.fieldKind){case"scalar":n.set(t,po(e,t.scalar,t.utf8Validation));break;case"enum":let o=po(e,W.INT32);if(t.enum.open)n.set(t,o);else if(t.enum.values.some(l=>l.number===o))n.set(t,o);else if(r.readUnknownFields){let l=[];Ma(o,l);let c=(s=n.getUnknown())!==null&&s!==void 0?s:[];c.push({no:t.number,wireType:i,data:new Uint8Array(l)}),n.setUnknown(c)}break;case"message":n.set(t,od(e,r,t,n.get(t)));break;case"list":AM(e,i,n.get(t),r);break;case"map":wM(e,n.get(t),r);break}}function wM(n,e,t){let i=e.field(),r,s,o=n.uint32(),a=n.pos+o;for(;n.pos<a;){let[l]=n.tag();switch(l){case 1:r=po(n,i.mapKey,i.utf8Validation);break;case 2:switch(i.mapKind){case"scalar":s=po(n,i.scalar,i.utf8Validation);break;case"enum":s=n.int32();break;case"message":s=od(n,t,i);break}break}}if(r===void 0&&(r=Gi(i.mapKey,!1)),s===void 0)switch(i.mapKind){case"scalar":s=Gi(i.scalar,!1);break;case"enum":s=i.enum.values[0].number;break;case"message":s=Wn(i.message,void 0,!1);break}e.set(r,s)}function AM(n,e,t,i){var r;let s=t.field();if(s.listKind==="message"){t.add(od(n,i,s));return}let o=(r=s.scalar)!==null&&r!==void 0?r:W.INT32;if(!(e==en.LengthDelimited&&o!=W.STRING&&o!=W.BYTES)){t.add(po(n,o,s.utf8Validation));return}let l=n.uint32()+n.pos;for(;n.pos<l;)t.add(po(n,o,s.utf8Validation))}function od(n,e,t,i){let r=t.delimitedEncoding,s=i??Wn(t.message,void 0,!1);return C0(s,n,e,r,r?t.number:n.uint32()),s}function po(n,e,t=!1){switch(e){case W.STRING:return n.string(t);case W.BOOL:return n.bool();case W.DOUBLE:return n.double();case W.FLOAT:return n.float();case W.INT32:return n.int32();case W.INT64:return n.int64();case W.UINT64:return n.uint64();case W.FIXED64:return n.fixed64();case W.BYTES:return n.bytes();case W.FIXED32:return n.fixed32();case W.SFIXED32:return n.sfixed32();case W.SFIXED64:return n.sfixed64();case W.SINT64:return n.sint64();case W.UINT32:return n.uint32();case W.SINT32:return n.sint32()}}function es(n,e){var t;let i=ii(I0,ho(n));return i.messageType.forEach(Ia),i.dependency=(t=e?.map(s=>s.proto.name))!==null&&t!==void 0?t:[],cc(i,s=>e?.find(o=>o.proto.name===s)).getFile(i.name)}var ad=es("Chlnb29nbGUvcHJvdG9idWYvYW55LnByb3RvEg9nb29nbGUucHJvdG9idWYiJgoDQW55EhAKCHR5cGVfdXJsGAEgASgJEg0KBXZhbHVlGAIgASgMQnYKE2NvbS5nb29nbGUucHJvdG9idWZCCEFueVByb3RvUAFaLGdvb2dsZS5nb2xhbmcub3JnL3Byb3RvYnVmL3R5cGVzL2tub3duL2FueXBiogIDR1BCqgIeR29vZ2xlLlByb3RvYnVmLldlbGxLbm93blR5cGVzYgZwcm90bzM"),N0=Xn(ad,0);var TM=3,P0={writeUnknownFields:!0};function RM(n){return n?Object.assign(Object.assign({},P0),n):P0}function mo(n,e,t){return hc(new co,RM(t),Wn(n,e)).finish()}function hc(n,e,t){var i;for(let r of t.sortedFields){if(!t.isSet(r)){if(r.presence==TM)throw new Error(`cannot encode ${r} to binary: required field not set`);continue}ld(n,e,t,r)}if(e.writeUnknownFields)for(let{no:r,wireType:s,data:o}of(i=t.getUnknown())!==null&&i!==void 0?i:[])n.tag(r,s).raw(o);return n}function ld(n,e,t,i){var r;switch(i.fieldKind){case"scalar":case"enum":fc(n,t.desc.typeName,i.name,(r=i.scalar)!==null&&r!==void 0?r:W.INT32,i.number,t.get(i));break;case"list":IM(n,e,i,t.get(i));break;case"message":L0(n,e,i,t.get(i));break;case"map":for(let[s,o]of t.get(i))CM(n,e,i,s,o);break}}function fc(n,e,t,i,r,s){D0(n.tag(r,NM(i)),e,t,i,s)}function L0(n,e,t,i){t.delimitedEncoding?hc(n.tag(t.number,en.StartGroup),e,i).tag(t.number,en.EndGroup):hc(n.tag(t.number,en.LengthDelimited).fork(),e,i).join()}function IM(n,e,t,i){var r;if(t.listKind=="message"){for(let o of i)L0(n,e,t,o);return}let s=(r=t.scalar)!==null&&r!==void 0?r:W.INT32;if(t.packed){if(!i.size)return;n.tag(t.number,en.LengthDelimited).fork();for(let o of i)D0(n,t.parent.typeName,t.name,s,o);n.join();return}for(let o of i)fc(n,t.parent.typeName,t.name,s,t.number,o)}function CM(n,e,t,i,r){var s;switch(n.tag(t.number,en.LengthDelimited).fork(),fc(n,t.parent.typeName,t.name,t.mapKey,1,i),t.mapKind){case"scalar":case"enum":fc(n,t.parent.typeName,t.name,(s=t.scalar)!==null&&s!==void 0?s:W.INT32,2,r);break;case"message":hc(n.tag(2,en.LengthDelimited).fork(),e,r).join();break}n.join()}function D0(n,e,t,i,r){try{switch(i){case W.STRING:n.string(r);break;case W.BOOL:n.bool(r);break;case W.DOUBLE:n.double(r);break;case W.FLOAT:n.float(r);break;case W.INT32:n.int32(r);break;case W.INT64:n.int64(r);break;case W.UINT64:n.uint64(r);break;case W.FIXED64:n.fixed64(r);break;case W.BYTES:n.bytes(r);break;case W.FIXED32:n.fixed32(r);break;case W.SFIXED32:n.sfixed32(r);break;case W.SFIXED64:n.sfixed64(r);break;case W.SINT64:n.sint64(r);break;case W.UINT32:n.uint32(r);break;case W.SINT32:n.sint32(r);break}}catch(s){throw s instanceof Error?new Error(`cannot encode field ${e}.${t} to binary: ${s.message}`):s}}function NM(n){switch(n){case W.BYTES:case W.STRING:return en.LengthDelimited;case W.DOUBLE:case W.FIXED64:case W.SFIXED64:return en.Bit64;case W.FIXED32:case W.SFIXED32:case W.FLOAT:return en.Bit32;default:return en.Varint}}function U0(n,e,t){let i=!1;return t||(t=yn(N0),i=!0),t.value=mo(n,e),t.typeUrl=DM(e.$typeName),i?t:void 0}function LM(n,e){if(n.typeUrl==="")return!1;let t=typeof e=="string"?e:e.typeName,i=F0(n.typeUrl);return t===i}function O0(n,e){if(n.typeUrl==="")return;let t=e.kind=="message"?e:e.getMessage(F0(n.typeUrl));if(!(!t||!LM(n,t)))return ii(t,n.value)}function DM(n){return`type.googleapis.com/${n}`}function F0(n){let e=n.lastIndexOf("/"),t=e>=0?n.substring(e+1):n;if(!t.length)throw new Error(`invalid type url: ${n}`);return t}var cd=es("Chxnb29nbGUvcHJvdG9idWYvc3RydWN0LnByb3RvEg9nb29nbGUucHJvdG9idWYihAEKBlN0cnVjdBIzCgZmaWVsZHMYASADKAsyIy5nb29nbGUucHJvdG9idWYuU3RydWN0LkZpZWxkc0VudHJ5GkUKC0ZpZWxkc0VudHJ5EgsKA2tleRgBIAEoCRIlCgV2YWx1ZRgCIAEoCzIWLmdvb2dsZS5wcm90b2J1Zi5WYWx1ZToCOAEi6gEKBVZhbHVlEjAKCm51bGxfdmFsdWUYASABKA4yGi5nb29nbGUucHJvdG9idWYuTnVsbFZhbHVlSAASFgoMbnVtYmVyX3ZhbHVlGAIgASgBSAASFgoMc3RyaW5nX3ZhbHVlGAMgASgJSAASFAoKYm9vbF92YWx1ZRgEIAEoCEgAEi8KDHN0cnVjdF92YWx1ZRgFIAEoCzIXLmdvb2dsZS5wcm90b2J1Zi5TdHJ1Y3RIABIwCgpsaXN0X3ZhbHVlGAYgASgLMhouZ29vZ2xlLnByb3RvYnVmLkxpc3RWYWx1ZUgAQgYKBGtpbmQiMwoJTGlzdFZhbHVlEiYKBnZhbHVlcxgBIAMoCzIWLmdvb2dsZS5wcm90b2J1Zi5WYWx1ZSobCglOdWxsVmFsdWUSDgoKTlVMTF9WQUxVRRAAQn8KE2NvbS5nb29nbGUucHJvdG9idWZCC1N0cnVjdFByb3RvUAFaL2dvb2dsZS5nb2xhbmcub3JnL3Byb3RvYnVmL3R5cGVzL2tub3duL3N0cnVjdHBi+AEBogIDR1BCqgIeR29vZ2xlLlByb3RvYnVmLldlbGxLbm93blR5cGVzYgZwcm90bzM"),B0=Xn(cd,0),ud=Xn(cd,1),k0=Xn(cd,2),dc;(function(n){n[n.NULL_VALUE=0]="NULL_VALUE"})(dc||(dc={}));function V0(n,e,t){z0(e,n);let i=UM(n.$unknown,e),[r,s,o]=go(e),a=rd(t);for(let l of i)sd(r,new As(l.data),s,l.wireType,a);return o()}function G0(n,e,t){var i;z0(e,n);let r=((i=n.$unknown)!==null&&i!==void 0?i:[]).filter(c=>c.no!==e.number),[s,o]=go(e,t),a=new co;ld(a,{writeUnknownFields:!0},s,o);let l=new As(a.finish());for(;l.pos<l.len;){let[c,u]=l.tag(),h=l.skip(u,c);r.push({no:c,wireType:u,data:h})}n.$unknown=r}function UM(n,e){if(n===void 0)return[];if(e.fieldKind==="enum"||e.fieldKind==="scalar"){for(let t=n.length-1;t>=0;--t)if(n[t].no==e.number)return[n[t]];return[]}return n.filter(t=>t.no===e.number)}function go(n,e){let t=n.typeName,i=Object.assign(Object.assign({},n),{kind:"field",parent:n.extendee,localName:t}),r=Object.assign(Object.assign({},n.extendee),{fields:[i],members:[i],oneofs:[]}),s=yn(r,e!==void 0?{[t]:e}:void 0);return[Wn(r,s),i,()=>{let o=s[t];if(o===void 0){let a=n.message;return Hi(a)?Gi(a.fields[0].scalar,a.fields[0].longAsString):yn(a)}return o}]}function z0(n,e){if(n.extendee.typeName!=e.$typeName)throw new Error(`extension ${n.typeName} can only be applied to message ${n.extendee.typeName}`)}var OM=3,FM=2,H0={alwaysEmitImplicit:!1,enumAsInteger:!1,useProtoFieldName:!1};function BM(n){return n?Object.assign(Object.assign({},H0),n):H0}function kM(n,e,t){return Pa(Wn(n,e),BM(t))}function X0(n,e,t){var i;let r=kM(n,e,t);return JSON.stringify(r,null,(i=t?.prettySpaces)!==null&&i!==void 0?i:0)}function Pa(n,e){var t;let i=Y0(n,e);if(i!==void 0)return i;let r={};for(let s of n.sortedFields){if(!n.isSet(s)){if(s.presence==OM)throw new Error(`cannot encode ${s} to JSON: required field not set`);if(!e.alwaysEmitImplicit||s.presence!==FM)continue}let o=W0(s,n.get(s),e);o!==void 0&&(r[zM(s,e)]=o)}if(e.registry){let s=new Set;for(let{no:o}of(t=n.getUnknown())!==null&&t!==void 0?t:[])if(!s.has(o)){s.add(o);let a=e.registry.getExtensionFor(n.desc,o);if(!a)continue;let l=V0(n.message,a),[c,u]=go(a,l),h=W0(u,c.get(u),e);h!==void 0&&(r[a.jsonName]=h)}}return r}function W0(n,e,t){switch(n.fieldKind){case"scalar":return pc(n,e);case"message":return Pa(e,t);case"enum":return hd(n.enum,e,t.enumAsInteger);case"list":return GM(e,t);case"map":return VM(e,t)}}function VM(n,e){let t=n.field(),i={};switch(t.mapKind){case"scalar":for(let[r,s]of n)i[r]=pc(t,s);break;case"message":for(let[r,s]of n)i[r]=Pa(s,e);break;case"enum":for(let[r,s]of n)i[r]=hd(t.enum,s,e.enumAsInteger);break}return e.alwaysEmitImplicit||n.size>0?i:void 0}function GM(n,e){let t=n.field(),i=[];switch(t.listKind){case"scalar":for(let r of n)i.push(pc(t,r));break;case"enum":for(let r of n)i.push(hd(t.enum,r,e.enumAsInteger));break;case"message":for(let r of n)i.push(Pa(r,e));break}return e.alwaysEmitImplicit||i.length>0?i:void 0}function hd(n,e,t){var i;if(typeof e!="number")throw new Error(`cannot encode ${n} to JSON: expected number, got ${xn(e)}`);if(n.typeName=="google.protobuf.NullValue")return null;if(t)return e;let r=n.value[e];return(i=r?.name)!==null&&i!==void 0?i:e}function pc(n,e){var t,i,r,s,o,a;switch(n.scalar){case W.INT32:case W.SFIXED32:case W.SINT32:case W.FIXED32:case W.UINT32:if(typeof e!="number")throw new Error(`cannot encode ${n} to JSON: ${(t=Ir(n,e))===null||t===void 0?void 0:t.message}`);return e;case W.FLOAT:case W.DOUBLE:if(typeof e!="number")throw new Error(`cannot encode ${n} to JSON: ${(i=Ir(n,e))===null||i===void 0?void 0:i.message}`);return Number.isNaN(e)?"NaN":e===Number.POSITIVE_INFINITY?"Infinity":e===Number.NEGATIVE_INFINITY?"-Infinity":e;case W.STRING:if(typeof e!="string")throw new Error(`cannot encode ${n} to JSON: ${(r=Ir(n,e))===null||r===void 0?void 0:r.message}`);return e;case W.BOOL:if(typeof e!="boolean")throw new Error(`cannot encode ${n} to JSON: ${(s=Ir(n,e))===null||s===void 0?void 0:s.message}`);return e;case W.UINT64:case W.FIXED64:case W.INT64:case W.SFIXED64:case W.SINT64:if(typeof e=="bigint"||typeof e=="string"||typeof e=="number"&&Number.isInteger(e))return e.toString();throw new Error(`cannot encode ${n} to JSON: ${(o=Ir(n,e))===null||o===void 0?void 0:o.message}`);case W.BYTES:if(e instanceof Uint8Array)return jf(e);throw new Error(`cannot encode ${n} to JSON: ${(a=Ir(n,e))===null||a===void 0?void 0:a.message}`)}}function zM(n,e){return e.useProtoFieldName?n.name:n.jsonName}function Y0(n,e){if(n.desc.typeName.startsWith("google.protobuf."))switch(n.desc.typeName){case"google.protobuf.Any":return HM(n.message,e);case"google.protobuf.Timestamp":return YM(n.message);case"google.protobuf.Duration":return WM(n.message);case"google.protobuf.FieldMask":return XM(n.message);case"google.protobuf.Struct":return Z0(n.message);case"google.protobuf.Value":return fd(n.message);case"google.protobuf.ListValue":return K0(n.message);default:if(Hi(n.desc)){let t=n.desc.fields[0];return pc(t,n.get(t))}return}}function HM(n,e){if(n.typeUrl==="")return{};let{registry:t}=e,i,r;if(t&&(i=O0(n,t),i&&(r=t.getMessage(i.$typeName))),!r||!i)throw new Error(`cannot encode message ${n.$typeName} to JSON: "${n.typeUrl}" is not in the type registry`);let s=Wn(r,i),o=tc(r)?{value:Y0(s,e)}:Pa(s,e);return o["@type"]=n.typeUrl,o}function WM(n){let e=Number(n.seconds),t=n.nanos;if(e>315576e6||e<-315576e6)throw new Error(`cannot encode message ${n.$typeName} to JSON: value out of range`);if(e>0&&t<0||e<0&&t>0)throw new Error(`cannot encode message ${n.$typeName} to JSON: nanos sign must match seconds sign`);let i=n.seconds.toString();if(t!==0){let r=Math.abs(t).toString();r="0".repeat(9-r.length)+r,r.substring(3)==="000000"?r=r.substring(0,3):r.substring(6)==="000"&&(r=r.substring(0,6)),i+="."+r,t<0&&e==0&&(i="-"+i)}return i+"s"}function XM(n){return n.paths.map(e=>{if(ac(Cr(e))!==e)throw new Error(`cannot encode message ${n.$typeName} to JSON: lowerCamelCase of path name "${e}" is irreversible`);return Cr(e)}).join(",")}function Z0(n){let e={};for(let[t,i]of Object.entries(n.fields))e[t]=fd(i);return e}function fd(n){switch(n.kind.case){case"nullValue":return null;case"numberValue":if(!Number.isFinite(n.kind.value))throw new Error(`${n.$typeName} cannot be NaN or Infinity`);return n.kind.value;case"boolValue":return n.kind.value;case"stringValue":return n.kind.value;case"structValue":return Z0(n.kind.value);case"listValue":return K0(n.kind.value);default:throw new Error(`${n.$typeName} must have a value`)}}function K0(n){return n.values.map(fd)}function YM(n){let e=Number(n.seconds)*1e3;if(e<Date.parse("0001-01-01T00:00:00Z")||e>Date.parse("9999-12-31T23:59:59Z"))throw new Error(`cannot encode message ${n.$typeName} to JSON: must be from 0001-01-01T00:00:00Z to 9999-12-31T23:59:59Z inclusive`);if(n.nanos<0)throw new Error(`cannot encode message ${n.$typeName} to JSON: nanos must not be negative`);if(n.nanos>999999999)throw new Error(`cannot encode message ${n.$typeName} to JSON: nanos must not be greater than 99999999`);let t="Z";if(n.nanos>0){let i=(n.nanos+1e9).toString().substring(1);i.substring(3)==="000000"?t="."+i.substring(0,3)+"Z":i.substring(6)==="000"?t="."+i.substring(0,6)+"Z":t="."+i+"Z"}return new Date(e).toISOString().replace(".000Z",t)}function ZM(n){return Object.assign(Object.assign({ignoreUnknownFields:!1,recursionLimit:100},n),{depth:0})}function q0(n,e,t){return KM(n,nE(e,n.typeName),t)}function KM(n,e,t){let i=Wn(n);try{La(i,e,ZM(t))}catch(r){throw Ug(r)?new Error(`cannot decode ${r.field()} from JSON: ${r.message}`,{cause:r}):r}return i.message}var dd=new WeakMap;function $M(n,e){var t;if(!dd.has(n)){let i=new Map;for(let r of n.fields)i.set(r.name,r).set(r.jsonName,r);dd.set(n,i)}return(t=dd.get(n))===null||t===void 0?void 0:t.get(e)}function La(n,e,t){var i;if(++t.depth>t.recursionLimit)throw new Error(`cannot decode ${n.desc} from JSON: maximum recursion depth of ${t.recursionLimit} reached`);if(rE(n,e,t)){t.depth--;return}if(e==null||Array.isArray(e)||typeof e!="object")throw new Error(`cannot decode ${n.desc} from JSON: ${xn(e)}`);let r=new Map,s=new Set;for(let[o,a]of Object.entries(e)){let l=$M(n.desc,o);if(l){if(s.has(l))throw new _n(l,"set multiple times");if(s.add(l),l.oneof&&a===null&&l.fieldKind=="scalar")continue;if(l.oneof){let c=r.get(l.oneof);if(c!==void 0)throw new _n(l.oneof,`oneof set multiple times by ${c.name} and ${l.name}`);r.set(l.oneof,l)}$0(n,l,a,t)}else{let c;if(o.startsWith("[")&&o.endsWith("]")&&(c=(i=t.registry)===null||i===void 0?void 0:i.getExtension(o.substring(1,o.length-1)))&&c.extendee.typeName===n.desc.typeName){let[u,h,f]=go(c);$0(u,h,a,t),G0(n.message,c,f())}if(!c&&!t.ignoreUnknownFields)throw new Error(`cannot decode ${n.desc} from JSON: key "${o}" is unknown`)}}t.depth--}function $0(n,e,t,i){switch(e.fieldKind){case"scalar":eE(n,e,t);break;case"enum":QM(n,e,t,i);break;case"message":jM(n,e,t,i);break;case"list":JM(n.get(e),t,i);break;case"map":qM(n.get(e),t,i);break}}function J0(n,e,t){if(n.scalar&&e!==null)return pd(n,e);if(n.message&&!mc(n,e)){let i=Wn(n.message);return La(i,e,t),i}if(n.enum&&!mc(n,e))return j0(n.enum,e,t.ignoreUnknownFields);throw new _n(n,`${n.fieldKind==="list"?"list item":"map value"} must not be null`)}function qM(n,e,t){if(e===null)return;let i=n.field();if(typeof e!="object"||Array.isArray(e))throw new _n(i,"expected object, got "+xn(e));let r=new Set;for(let[s,o]of Object.entries(e)){let a=tE(i.mapKey,s);if(r.has(a))throw new _n(i,`duplicate map key "${s}"`);r.add(a);let l=J0(i,o,t);l!==gc&&n.set(a,l)}}function JM(n,e,t){if(e===null)return;let i=n.field();if(!Array.isArray(e))throw new _n(i,"expected Array, got "+xn(e));for(let r of e){let s=J0(i,r,t);s!==gc&&n.add(s)}}function jM(n,e,t,i){if(mc(e,t)){n.clear(e);return}let r=n.isSet(e)?n.get(e):Wn(e.message);La(r,t,i),n.set(e,r)}function QM(n,e,t,i){if(mc(e,t)){n.clear(e);return}let r=j0(e.enum,t,i.ignoreUnknownFields);r!==gc&&n.set(e,r)}function eE(n,e,t){t===null?n.clear(e):n.set(e,pd(e,t))}function mc(n,e){var t,i;return e===null&&((t=n.message)===null||t===void 0?void 0:t.typeName)!="google.protobuf.Value"&&((i=n.enum)===null||i===void 0?void 0:i.typeName)!="google.protobuf.NullValue"}var gc=Symbol();function j0(n,e,t){if(e===null)return n.values[0].number;switch(typeof e){case"number":if(Number.isInteger(e))return e;break;case"string":let i=n.values.find(r=>r.name===e);if(i!==void 0)return i.number;if(t)return gc;break}throw new Error(`cannot decode ${n} from JSON: ${xn(e)}`)}function pd(n,e){switch(n.scalar){case W.DOUBLE:case W.FLOAT:if(e==="NaN")return NaN;if(e==="Infinity")return Number.POSITIVE_INFINITY;if(e==="-Infinity")return Number.NEGATIVE_INFINITY;if(typeof e=="number"){if(Number.isNaN(e))throw new _n(n,"unexpected NaN number");if(!Number.isFinite(e))throw new _n(n,"unexpected infinite number");break}if(typeof e=="string"){if(e===""||e.trim().length!==e.length)break;let t=Number(e);if(!Number.isFinite(t))break;return t}break;case W.INT32:case W.FIXED32:case W.SFIXED32:case W.SINT32:case W.UINT32:return Q0(e);case W.BYTES:if(typeof e=="string"){if(e==="")return new Uint8Array(0);try{return ho(e)}catch(t){let i=t instanceof Error?t.message:String(t);throw new _n(n,i)}}break}return e}function tE(n,e){switch(n){case W.BOOL:switch(e){case"true":return!0;case"false":return!1}return e;case W.INT32:case W.FIXED32:case W.UINT32:case W.SFIXED32:case W.SINT32:return Q0(e);case W.INT64:case W.SINT64:case W.SFIXED64:case W.UINT64:case W.FIXED64:return/^-?0+$/.test(e)?"0":e.replace(/^(-?)0+(?=\d)/,"$1");default:return e}}function Q0(n){if(typeof n=="string"){if(n===""||n.trim().length!==n.length)return n;let e=Number(n);return Number.isNaN(e)?n:e}return n}function nE(n,e){let t;try{t=JSON.parse(n)}catch(i){let r=i instanceof Error?i.message:String(i);throw new Error(`cannot decode message ${e} from JSON: ${r}`,{cause:i})}return iE(n,e),t}function iE(n,e){let t=[],i=!1,r=0;for(;r<n.length;)switch(n[r]){case"{":t.push(new Set),i=!0,r++;break;case"[":t.push(null),i=!1,r++;break;case"}":case"]":t.pop(),i=!1,r++;break;case",":i=t[t.length-1]!=null,r++;break;case":":i=!1,r++;break;case'"':{let s=r++,o=!1;for(;r<n.length;){if(n[r]=="\\"){o=!0,r+=2;continue}if(n[r]=='"')break;r++}let a=r++,l=t[t.length-1];if(i&&l){let c=o?JSON.parse(n.substring(s,a+1)):n.substring(s+1,a);if(l.has(c))throw new Error(`cannot decode message ${e} from JSON: duplicate object key "${c}"`);l.add(c)}i=!1;break}default:r++;break}}function rE(n,e,t){if(!n.desc.typeName.startsWith("google.protobuf."))return!1;switch(n.desc.typeName){case"google.protobuf.Any":return sE(n.message,e,t),!0;case"google.protobuf.Timestamp":return oE(n.message,e),!0;case"google.protobuf.Duration":return aE(n.message,e),!0;case"google.protobuf.FieldMask":return lE(n.message,e),!0;case"google.protobuf.Struct":return ey(n.message,e,t),!0;case"google.protobuf.Value":return md(n.message,e,t),!0;case"google.protobuf.ListValue":return ty(n.message,e,t),!0;default:if(Hi(n.desc)){let i=n.desc.fields[0];return e===null?n.clear(i):n.set(i,pd(i,e)),!0}return!1}}function sE(n,e,t){var i;if(e===null||Array.isArray(e)||typeof e!="object")throw new Error(`cannot decode message ${n.$typeName} from JSON: expected object but got ${xn(e)}`);if(Object.keys(e).length==0)return;let r=e["@type"];if(typeof r!="string"||r=="")throw new Error(`cannot decode message ${n.$typeName} from JSON: "@type" is empty`);let s=r.includes("/")?r.substring(r.lastIndexOf("/")+1):r;if(!s.length)throw new Error(`cannot decode message ${n.$typeName} from JSON: "@type" is invalid`);let o=(i=t.registry)===null||i===void 0?void 0:i.getMessage(s);if(!o)throw new Error(`cannot decode message ${n.$typeName} from JSON: ${r} is not in the type registry`);let a=Wn(o);if(tc(o)&&Object.prototype.hasOwnProperty.call(e,"value")){let l=e.value;La(a,l,t)}else{let l=Object.assign({},e);delete l["@type"],La(a,l,t)}U0(a.desc,a.message,n)}function oE(n,e){if(typeof e!="string")throw new Error(`cannot decode message ${n.$typeName} from JSON: ${xn(e)}`);let t=e.match(/^([0-9]{4})-([0-9]{2})-([0-9]{2})T([0-9]{2}):([0-9]{2}):([0-9]{2})(?:\.([0-9]{1,9}))?(?:Z|([+-][0-9][0-9]:[0-9][0-9]))$/);if(!t)throw new Error(`cannot decode message ${n.$typeName} from JSON: invalid RFC 3339 string`);let i=Date.parse(t[1]+"-"+t[2]+"-"+t[3]+"T"+t[4]+":"+t[5]+":"+t[6]+(t[8]?t[8]:"Z"));if(Number.isNaN(i))throw new Error(`cannot decode message ${n.$typeName} from JSON: invalid RFC 3339 string`);if(i<Date.parse("0001-01-01T00:00:00Z")||i>Date.parse("9999-12-31T23:59:59Z"))throw new Error(`cannot decode message ${n.$typeName} from JSON: must be from 0001-01-01T00:00:00Z to 9999-12-31T23:59:59Z inclusive`);n.seconds=Rt.parse(i/1e3),n.nanos=0,t[7]&&(n.nanos=parseInt("1"+t[7]+"0".repeat(9-t[7].length))-1e9)}function aE(n,e){if(typeof e!="string")throw new Error(`cannot decode message ${n.$typeName} from JSON: ${xn(e)}`);let t=e.match(/^(-?[0-9]+)(?:\.([0-9]+))?s/);if(t===null)throw new Error(`cannot decode message ${n.$typeName} from JSON: ${xn(e)}`);let i=Number(t[1]);if(i>315576e6||i<-315576e6)throw new Error(`cannot decode message ${n.$typeName} from JSON: ${xn(e)}`);if(n.seconds=Rt.parse(i),typeof t[2]!="string")return;let r=t[2]+"0".repeat(9-t[2].length);n.nanos=parseInt(r),(i<0||Object.is(i,-0))&&(n.nanos=-n.nanos)}function lE(n,e){if(typeof e!="string")throw new Error(`cannot decode message ${n.$typeName} from JSON: ${xn(e)}`);e!==""&&(n.paths=e.split(",").map(t=>{if(t.includes("_"))throw new Error(`cannot decode message ${n.$typeName} from JSON: path names must be lowerCamelCase`);return ac(t)}))}function ey(n,e,t){if(typeof e!="object"||e==null||Array.isArray(e))throw new Error(`cannot decode message ${n.$typeName} from JSON ${xn(e)}`);for(let[i,r]of Object.entries(e)){let s=yn(ud);md(s,r,t),n.fields[i]=s}}function md(n,e,t){if(++t.depth>t.recursionLimit)throw new Error(`cannot decode ${n.$typeName} from JSON: maximum recursion depth of ${t.recursionLimit} reached`);switch(typeof e){case"number":n.kind={case:"numberValue",value:e};break;case"string":n.kind={case:"stringValue",value:e};break;case"boolean":n.kind={case:"boolValue",value:e};break;case"object":if(e===null)n.kind={case:"nullValue",value:dc.NULL_VALUE};else if(Array.isArray(e)){let i=yn(k0);ty(i,e,t),n.kind={case:"listValue",value:i}}else{let i=yn(B0);ey(i,e,t),n.kind={case:"structValue",value:i}}break;default:throw new Error(`cannot decode message ${n.$typeName} from JSON ${xn(e)}`)}return t.depth--,n}function ty(n,e,t){if(!Array.isArray(e))throw new Error(`cannot decode message ${n.$typeName} from JSON ${xn(e)}`);for(let i of e){let r=yn(ud);md(r,i,t),n.values.push(r)}}function gd(n){let e=Je[n];return typeof e!="string"?n.toString():e[0].toLowerCase()+e.substring(1).replace(/[A-Z]/g,t=>"_"+t.toLowerCase())}var bt=class n extends Error{constructor(e,t=Je.Unknown,i,r,s){super(cE(e,t)),this.name="ConnectError",this.isWireError=!1,Object.setPrototypeOf(this,new.target.prototype),this.rawMessage=e,this.code=t,this.metadata=new Headers(i??{}),this.details=r??[],this.cause=s}static from(e,t=Je.Unknown){return e instanceof n?e:e instanceof Error?e.name=="AbortError"||e.name=="TimeoutError"?new n(e.message,Je.Canceled):new n(e.message,t,void 0,void 0,e):new n(String(e),t,void 0,void 0,e)}static[Symbol.hasInstance](e){return e instanceof Error?Object.getPrototypeOf(e)===n.prototype?!0:e.name==="ConnectError"&&"code"in e&&typeof e.code=="number"&&"metadata"in e&&"details"in e&&Array.isArray(e.details)&&"rawMessage"in e&&typeof e.rawMessage=="string"&&"cause"in e:!1}findDetails(e){let t=e.kind==="message"?{getMessage:r=>r===e.typeName?e:void 0}:e,i=[];for(let r of this.details){if("desc"in r){t.getMessage(r.desc.typeName)&&i.push(yn(r.desc,r.value));continue}let s=t.getMessage(r.type);if(s)try{i.push(ii(s,r.value))}catch{}}return i}};function cE(n,e){return n.length?`[${gd(e)}] ${n}`:`[${gd(e)}]`}function ny(n,e,t){try{let i=ho(n);return e?ii(e,i,t):i}catch(i){throw bt.from(i,Je.DataLoss)}}function iy(n,e){let t={};for(let i of n.methods){let r=e(i);r!=null&&(t[i.localName]=r)}return t}var yc=1;function ry(n,e,t=!1){if(e>n){let i=`message size is larger than configured readMaxBytes ${n}`;throw t&&(i=`message size ${e} is larger than configured readMaxBytes ${n}`),new bt(i,Je.ResourceExhausted)}}function uE(n){return new yd(n)}var yd=class{constructor(e){this.readMaxBytes=e,this.header=new Uint8Array(5),this.headerView=new DataView(this.header.buffer),this.buf=[]}get byteLength(){return this.buf.reduce((e,t)=>e+t.byteLength,0)}decode(e){this.buf.push(e);let t=[];for(;;){let i=this.pop();if(!i)break;t.push(i)}return t}pop(){if(!(!this.env&&(this.env=this.head(),!this.env))&&this.cons(this.env.data)){let e=this.env;return this.env=void 0,e}}head(){if(!this.cons(this.header))return;let e=this.headerView.getUint8(0),t=this.headerView.getUint32(1);return ry(this.readMaxBytes,t,!0),{flags:e,data:new Uint8Array(t)}}cons(e){let t=e.byteLength;if(this.byteLength<t)return!1;let i=0;for(;i<t;){let r=this.buf.shift();r.byteLength>t-i?(e.set(r.subarray(0,t-i),i),this.buf.unshift(r.subarray(t-i)),i+=t-i):(e.set(r,i),i+=r.byteLength)}return!0}};function _c(n){let e,t=uE(4294967295);return new ReadableStream({start(){e=n.getReader()},async pull(i){let r=!1;for(;!r;){let s=await e.read();if(s.done)t.byteLength>0&&i.error(new bt("protocol error: incomplete envelope",Je.InvalidArgument)),i.close();else for(let o of t.decode(s.value))i.enqueue(o),r=!0}}})}function xc(n,e){let t=new Uint8Array(e.length+5);t.set(e,5);let i=new DataView(t.buffer,t.byteOffset,t.byteLength);return i.setUint8(0,n),i.setUint32(1,e.length),t}var hE=function(n){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var e=n[Symbol.asyncIterator],t;return e?e.call(n):(n=typeof __values=="function"?__values(n):n[Symbol.iterator](),t={},i("next"),i("throw"),i("return"),t[Symbol.asyncIterator]=function(){return this},t);function i(s){t[s]=n[s]&&function(o){return new Promise(function(a,l){o=n[s](o),r(a,l,o.done,o.value)})}}function r(s,o,a,l){Promise.resolve(l).then(function(c){s({value:c,done:a})},o)}},Da=function(n){return this instanceof Da?(this.v=n,this):new Da(n)},fE=function(n,e,t){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var i=t.apply(n,e||[]),r,s=[];return r=Object.create((typeof AsyncIterator=="function"?AsyncIterator:Object).prototype),a("next"),a("throw"),a("return",o),r[Symbol.asyncIterator]=function(){return this},r;function o(d){return function(p){return Promise.resolve(p).then(d,h)}}function a(d,p){i[d]&&(r[d]=function(x){return new Promise(function(m,g){s.push([d,x,m,g])>1||l(d,x)})},p&&(r[d]=p(r[d])))}function l(d,p){try{c(i[d](p))}catch(x){f(s[0][3],x)}}function c(d){d.value instanceof Da?Promise.resolve(d.value.v).then(u,h):f(s[0][2],d)}function u(d){l("next",d)}function h(d){l("throw",d)}function f(d,p){d(p),s.shift(),s.length&&l(s[0][0],s[0][1])}},dE=function(n){var e,t;return e={},i("next"),i("throw",function(r){throw r}),i("return"),e[Symbol.iterator]=function(){return this},e;function i(r,s){e[r]=n[r]?function(o){return(t=!t)?{value:Da(n[r](o)),done:!1}:s?s(o):o}:s}};function sy(n){return fE(this,arguments,function*(){yield Da(yield*dE(hE(n)))})}var oy=function(n){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var e=n[Symbol.asyncIterator],t;return e?e.call(n):(n=typeof __values=="function"?__values(n):n[Symbol.iterator](),t={},i("next"),i("throw"),i("return"),t[Symbol.asyncIterator]=function(){return this},t);function i(s){t[s]=n[s]&&function(o){return new Promise(function(a,l){o=n[s](o),r(a,l,o.done,o.value)})}}function r(s,o,a,l){Promise.resolve(l).then(function(c){s({value:c,done:a})},o)}},yo=function(n){return this instanceof yo?(this.v=n,this):new yo(n)},pE=function(n){var e,t;return e={},i("next"),i("throw",function(r){throw r}),i("return"),e[Symbol.iterator]=function(){return this},e;function i(r,s){e[r]=n[r]?function(o){return(t=!t)?{value:yo(n[r](o)),done:!1}:s?s(o):o}:s}},mE=function(n,e,t){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var i=t.apply(n,e||[]),r,s=[];return r=Object.create((typeof AsyncIterator=="function"?AsyncIterator:Object).prototype),a("next"),a("throw"),a("return",o),r[Symbol.asyncIterator]=function(){return this},r;function o(d){return function(p){return Promise.resolve(p).then(d,h)}}function a(d,p){i[d]&&(r[d]=function(x){return new Promise(function(m,g){s.push([d,x,m,g])>1||l(d,x)})},p&&(r[d]=p(r[d])))}function l(d,p){try{c(i[d](p))}catch(x){f(s[0][3],x)}}function c(d){d.value instanceof yo?Promise.resolve(d.value.v).then(u,h):f(s[0][2],d)}function u(d){l("next",d)}function h(d){l("throw",d)}function f(d,p){d(p),s.shift(),s.length&&l(s[0][0],s[0][1])}};function _o(n,e){return iy(n,t=>{switch(t.methodKind){case"unary":return gE(e,t);case"server_streaming":return yE(e,t);case"client_streaming":return _E(e,t);case"bidi_streaming":return xE(e,t);default:return null}})}function gE(n,e){return async(t,i)=>{var r,s;let o=await n.unary(e,i?.signal,i?.timeoutMs,i?.headers,t,i?.contextValues);return(r=i?.onHeader)===null||r===void 0||r.call(i,o.header),(s=i?.onTrailer)===null||s===void 0||s.call(i,o.trailer),o.message}}function yE(n,e){return(t,i)=>ay(n.stream(e,i?.signal,i?.timeoutMs,i?.headers,sy([t]),i?.contextValues),i)}function _E(n,e){return async(t,i)=>{var r,s,o,a,l,c;let u=await n.stream(e,i?.signal,i?.timeoutMs,i?.headers,t,i?.contextValues);(l=i?.onHeader)===null||l===void 0||l.call(i,u.header);let h,f=0;try{for(var d=!0,p=oy(u.message),x;x=await p.next(),r=x.done,!r;d=!0)a=x.value,d=!1,h=a,f++}catch(m){s={error:m}}finally{try{!d&&!r&&(o=p.return)&&await o.call(p)}finally{if(s)throw s.error}}if(!h)throw new bt("protocol error: missing response message",Je.Unimplemented);if(f>1)throw new bt("protocol error: received extra messages for client streaming method",Je.Unimplemented);return(c=i?.onTrailer)===null||c===void 0||c.call(i,u.trailer),h}}function xE(n,e){return(t,i)=>ay(n.stream(e,i?.signal,i?.timeoutMs,i?.headers,t,i?.contextValues),i)}function ay(n,e){let t=(function(){return mE(this,arguments,function*(){var i,r;let s=yield yo(n);(i=e?.onHeader)===null||i===void 0||i.call(e,s.header),yield yo(yield*pE(oy(s.message))),(r=e?.onTrailer)===null||r===void 0||r.call(e,s.trailer)})})()[Symbol.asyncIterator]();return{[Symbol.asyncIterator]:()=>({next:()=>t.next()})}}function ly(...n){let e=new AbortController,t=n.filter(r=>r!==void 0).concat(e.signal);for(let r of t){if(r.aborted){i.apply(r);break}r.addEventListener("abort",i)}function i(){e.signal.aborted||e.abort(vc(this));for(let r of t)r.removeEventListener("abort",i)}return e}function cy(n){let e=new AbortController,t=()=>{e.abort(new bt("the operation timed out",Je.DeadlineExceeded))},i;return n!==void 0&&(n<=0?t():i=setTimeout(t,n)),{signal:e.signal,cleanup:()=>clearTimeout(i)}}function vc(n){if(!n.aborted)return;if(n.reason!==void 0)return n.reason;let e=new Error("This operation was aborted");return e.name="AbortError",e}function bc(){return{get(n){return n.id in this?this[n.id]:n.defaultValue},set(n,e){return this[n.id]=e,this},delete(n){return delete this[n.id],this}}}function Sc(n){let e=new Headers,t=new TextDecoder().decode(n).split(`\r
`);for(let i of t){if(i==="")continue;let r=i.indexOf(":");if(r>0){let s=i.substring(0,r).trim(),o=i.substring(r+1).trim();e.append(s,o)}}return e}var _d="Content-Type";var xd="Grpc-Timeout",Xi="Grpc-Status",Ua="Grpc-Message";var vd="Grpc-Status-Details-Bin";var Mc="User-Agent";var bd="X-User-Agent",hy="X-Grpc-Web";var fy="application/grpc-web+proto",dy="application/grpc-web+json";function Oa(n,e,...t){if(t.length>0)throw new Error;return n.services[e]}var bE=es("CgxzdGF0dXMucHJvdG8SCmdvb2dsZS5ycGMiTgoGU3RhdHVzEgwKBGNvZGUYASABKAUSDwoHbWVzc2FnZRgCIAEoCRIlCgdkZXRhaWxzGAMgAygLMhQuZ29vZ2xlLnByb3RvYnVmLkFueUJeCg5jb20uZ29vZ2xlLnJwY0ILU3RhdHVzUHJvdG9QAVo3Z29vZ2xlLmdvbGFuZy5vcmcvZ2VucHJvdG8vZ29vZ2xlYXBpcy9ycGMvc3RhdHVzO3N0YXR1c6ICA1JQQ2IGcHJvdG8z",[ad]),py=Xn(bE,0);var my="0";function Ec(n){var e;let t=n.get(vd);if(t!=null){let r=ny(t,py);if(r.code==0)return;let s=new bt(r.message,r.code,n);return s.details=r.details.map(o=>({type:o.typeUrl.substring(o.typeUrl.lastIndexOf("/")+1),value:o.value})),s.isWireError=!0,s}let i=n.get(Xi);if(i!=null){if(i===my)return;let r=parseInt(i,10),s;return r in Je?s=new bt(decodeURIComponent((e=n.get(Ua))!==null&&e!==void 0?e:""),r,n):s=new bt(`invalid grpc-status: ${i}`,Je.Internal,n),s.isWireError=!0,s}}function wc(n,e){return n.toString().replace(/\/?$/,`/${e.parent.typeName}/${e.name}`)}function Sd(n,e){return yn(n,e)}function gy(n,e){function t(i){return i.done===!0?i:{done:i.done,value:Sd(n,i.value)}}return{[Symbol.asyncIterator](){let i=e[Symbol.asyncIterator](),r={next:()=>i.next().then(t)};return i.throw!==void 0&&(r.throw=s=>i.throw(s).then(t)),i.return!==void 0&&(r.return=s=>i.return(s).then(t)),r}}}function Md(n,e){if(!e)return n;for(let t of e.concat().reverse())n=t(n);return n}function xy(n){var e;let t=Object.assign({},n);return(e=t.ignoreUnknownFields)!==null&&e!==void 0||(t.ignoreUnknownFields=!0),t}function Ac(n,e,t,i){let r=e?yy(n.input,i):_y(n.input,t);return{parse:(e?yy(n.output,i):_y(n.output,t)).parse,serialize:r.serialize}}function yy(n,e){return{parse(t){try{return ii(n,t,e)}catch(i){let r=i instanceof Error?i.message:String(i);throw new bt(`parse binary: ${r}`,Je.Internal)}},serialize(t){try{return mo(n,t,e)}catch(i){let r=i instanceof Error?i.message:String(i);throw new bt(`serialize binary: ${r}`,Je.Internal)}}}}function _y(n,e){var t,i;let r=(t=e?.textEncoder)!==null&&t!==void 0?t:new TextEncoder,s=(i=e?.textDecoder)!==null&&i!==void 0?i:new TextDecoder,o=xy(e);return{parse(a){try{let l=s.decode(a);return q0(n,l,o)}catch(l){throw bt.from(l,Je.InvalidArgument)}},serialize(a){try{let l=X0(n,a,o);return r.encode(l)}catch(l){throw bt.from(l,Je.Internal)}}}}function Ed(n){let e=Md(n.next,n.interceptors),[t,i,r]=vy(n),s=Object.assign(Object.assign({},n.req),{message:Sd(n.req.method.input,n.req.message),signal:t});return e(s).then(o=>(r(),o),i)}function wd(n){let e=Md(n.next,n.interceptors),[t,i,r]=vy(n),s=Object.assign(Object.assign({},n.req),{message:gy(n.req.method.input,n.req.message),signal:t}),o=!1;return t.addEventListener("abort",function(){var a,l;let c=n.req.message[Symbol.asyncIterator]();o||(a=c.throw)===null||a===void 0||a.call(c,this.reason).catch(()=>{}),(l=c.return)===null||l===void 0||l.call(c).catch(()=>{})}),e(s).then(a=>Object.assign(Object.assign({},a),{message:{[Symbol.asyncIterator](){let l=a.message[Symbol.asyncIterator]();return{next(){return!o&&t.aborted?i(vc(t)):l.next().then(c=>(c.done==!0&&(o=!0,r()),c),i)}}}}}),i)}function vy(n){let{signal:e,cleanup:t}=cy(n.timeoutMs),i=ly(n.signal,e);return[i.signal,function(s){let o=i.signal.aborted?bt.from(vc(i.signal),Je.Canceled):bt.from(s);return i.abort(o),t(),Promise.reject(o)},function(){t(),i.abort()}]}function by(){try{new Headers}catch{throw new Error("connect-web requires the fetch API. Are you running on an old version of Node.js? Node.js is not supported in Connect for Web - please stay tuned for Connect for Node.")}}function Fa(n,e){let t=Ec(n);if(t)throw e.forEach((i,r)=>{t.metadata.append(r,i)}),t;if(!e.has(Xi)&&!n.has(Xi))throw new bt("protocol error: missing status",Je.Internal)}function Tc(n,e,t,i){var r,s;let o=new Headers(t??{});o.set(_d,n?fy:dy),o.set(hy,"1");let a=(s=(r=o.get(Mc))!==null&&r!==void 0?r:o.get(bd))!==null&&s!==void 0?s:"connect-es/2.2.0";return o.set(bd,a),i&&o.set(Mc,a),e!==void 0&&o.set(xd,`${e}m`),o}function Sy(n){switch(n){case 400:return Je.Internal;case 401:return Je.Unauthenticated;case 403:return Je.PermissionDenied;case 404:return Je.Unimplemented;case 429:return Je.Unavailable;case 502:return Je.Unavailable;case 503:return Je.Unavailable;case 504:return Je.Unavailable;default:return Je.Unknown}}function Rc(n,e){var t;if(n>=200&&n<300)return{foundStatus:e.has(Xi),headerError:Ec(e)};throw new bt(decodeURIComponent((t=e.get(Ua))!==null&&t!==void 0?t:`HTTP ${n}`),Sy(n),e)}var Rs=function(n){return this instanceof Rs?(this.v=n,this):new Rs(n)},SE=function(n,e,t){if(!Symbol.asyncIterator)throw new TypeError("Symbol.asyncIterator is not defined.");var i=t.apply(n,e||[]),r,s=[];return r=Object.create((typeof AsyncIterator=="function"?AsyncIterator:Object).prototype),a("next"),a("throw"),a("return",o),r[Symbol.asyncIterator]=function(){return this},r;function o(d){return function(p){return Promise.resolve(p).then(d,h)}}function a(d,p){i[d]&&(r[d]=function(x){return new Promise(function(m,g){s.push([d,x,m,g])>1||l(d,x)})},p&&(r[d]=p(r[d])))}function l(d,p){try{c(i[d](p))}catch(x){f(s[0][3],x)}}function c(d){d.value instanceof Rs?Promise.resolve(d.value.v).then(u,h):f(s[0][2],d)}function u(d){l("next",d)}function h(d){l("throw",d)}function f(d,p){d(p),s.shift(),s.length&&l(s[0][0],s[0][1])}},My={redirect:"error"};function Ad(n){var e;by();let t=(e=n.useBinaryFormat)!==null&&e!==void 0?e:!0;return{async unary(i,r,s,o,a,l){let{serialize:c,parse:u}=Ac(i,t,n.jsonOptions,n.binaryOptions);return s=s===void 0?n.defaultTimeoutMs:s<=0?void 0:s,await Ed({interceptors:n.interceptors,signal:r,timeoutMs:s,req:{stream:!1,service:i.parent,method:i,requestMethod:"POST",url:wc(n.baseUrl,i),header:Tc(t,s,o,!1),contextValues:l??bc(),message:a},next:async h=>{var f;let p=await((f=n.fetch)!==null&&f!==void 0?f:globalThis.fetch)(h.url,Object.assign(Object.assign({},My),{method:h.requestMethod,headers:h.header,signal:h.signal,body:xc(0,c(h.message))})),{headerError:x}=Rc(p.status,p.headers);if(!p.body)throw x!==void 0?x:"missing response body";let m=_c(p.body).getReader(),g,v;for(;;){let T=await m.read();if(T.done)break;let{flags:M,data:R}=T.value;if((M&yc)===yc)throw new bt("protocol error: received unsupported compressed output",Je.Internal);if(M===128){if(g!==void 0)throw"extra trailer";g=Sc(R);continue}if(v!==void 0)throw new bt("extra message",Je.Unimplemented);v=u(R)}if(g===void 0)throw x!==void 0?x:new bt("missing trailer",p.headers.has(Xi)?Je.Unimplemented:Je.Unknown);if(Fa(g,p.headers),v===void 0)throw new bt("missing message",g.has(Xi)?Je.Unimplemented:Je.Unknown);return{stream:!1,service:i.parent,method:i,header:p.headers,message:v,trailer:g}}})},async stream(i,r,s,o,a,l){let{serialize:c,parse:u}=Ac(i,t,n.jsonOptions,n.binaryOptions);function h(d,p,x,m,g){return SE(this,arguments,function*(){let T=_c(d).getReader();if(p){if(!(yield Rs(T.read())).done)throw"extra data for trailers-only";return yield Rs(void 0)}let M=!1;for(;;){let R=yield Rs(T.read());if(R.done)break;let{flags:w,data:y}=R.value;if((w&128)===128){if(M)throw"extra trailer";M=!0;let A=Sc(y);Fa(A,m),A.forEach((k,D)=>x.set(D,k));continue}if(M)throw"extra message";yield yield Rs(u(y))}if("throwIfAborted"in g&&g.throwIfAborted(),!M)throw"missing trailer"})}async function f(d){if(i.methodKind!="server_streaming")throw"The fetch API does not support streaming request bodies";let p=await d[Symbol.asyncIterator]().next();if(p.done==!0)throw"missing request message";return xc(0,c(p.value))}return s=s===void 0?n.defaultTimeoutMs:s<=0?void 0:s,wd({interceptors:n.interceptors,signal:r,timeoutMs:s,req:{stream:!0,service:i.parent,method:i,requestMethod:"POST",url:wc(n.baseUrl,i),header:Tc(t,s,o,!1),contextValues:l??bc(),message:a},next:async d=>{var p;let m=await((p=n.fetch)!==null&&p!==void 0?p:globalThis.fetch)(d.url,Object.assign(Object.assign({},My),{method:d.requestMethod,headers:d.header,signal:d.signal,body:await f(d.message)})),{foundStatus:g,headerError:v}=Rc(m.status,m.headers);if(v!=null)throw v;if(!m.body)throw"missing response body";let T=new Headers;return Object.assign(Object.assign({},d),{header:m.headers,trailer:T,message:h(m.body,g,T,m.headers,d.signal)})}})}}}var Pr=es("ChxuZWVkbGVzaW0vdjEvbmVlZGxlc2ltLnByb3RvEgxuZWVkbGVzaW0udjEiNAoFUG9zZTISCwoDeF9tGAEgASgBEgsKA3lfbRgCIAEoARIRCgl0aGV0YV9yYWQYAyABKAEiHAoEVmVjMhIJCgF4GAEgASgBEgkKAXkYAiABKAEiJwoEVmVjMxIJCgF4GAEgASgBEgkKAXkYAiABKAESCQoBehgDIAEoASI4CgpRdWF0ZXJuaW9uEgkKAXcYASABKAESCQoBeBgCIAEoARIJCgF5GAMgASgBEgkKAXoYBCABKAEiXgoFUG9zZTMSJgoKcG9zaXRpb25fbRgBIAEoCzISLm5lZWRsZXNpbS52MS5WZWMzEi0KC29yaWVudGF0aW9uGAIgASgLMhgubmVlZGxlc2ltLnYxLlF1YXRlcm5pb24iUAoPVXBsb2FkZWRTY2VuZTNkEhIKCnNjZW5lX3RvbWwYASABKAkSFgoObWVzaF9maWxlX25hbWUYAiABKAkSEQoJbWVzaF90ZXh0GAMgASgJImAKBE1lc2gSEQoJbm9kZV94eV9tGAEgAygBEhYKDnRyaWFuZ2xlX25vZGVzGAIgAygNEhcKD3RyaWFuZ2xlX3JlZ2lvbhgDIAMoDRIUCgxyZWdpb25fbmFtZXMYBCADKAki5QEKBlJlZ2lvbhIMCgRuYW1lGAEgASgJEhgKEHlvdW5nX21vZHVsdXNfcGEYAiABKAESFQoNcG9pc3Nvbl9yYXRpbxgDIAEoARIYChBmcmljdGlvbl9uX3Blcl9tGAQgASgBEh0KFXN0YXRpY19mcmljdGlvbl9yYXRpbxgFIAEoARIWCg50aXBfcGVha19yYXRpbxgGIAEoARIYChB0aXBfcGVha193aWR0aF9tGAcgASgBEhgKEHB1bmN0dXJlX2ZvcmNlX24YCCABKAESFwoPY3V0dGluZ19mb3JjZV9uGAkgASgBIk4KBlRhcmdldBIMCgRuYW1lGAEgASgJEiQKCGNlbnRlcl9tGAIgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISEAoIcmFkaXVzX20YAyABKAEi6gIKDVVwbG9hZGVkU2NlbmUSDAoEbmFtZRgBIAEoCRIgCgRtZXNoGAIgASgLMhIubmVlZGxlc2ltLnYxLk1lc2gSJQoHcmVnaW9ucxgDIAMoCzIULm5lZWRsZXNpbS52MS5SZWdpb24SEwoLZml4ZWRfbm9kZXMYBCADKA0SDQoFcGxhbmUYBSABKAkSEwoLdGhpY2tuZXNzX20YBiABKAESFwoPbmVlZGxlX2xlbmd0aF9tGAcgASgBEigKC25lZWRsZV9iYXNlGAggASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEhgKEGNhcHR1cmVfcmFkaXVzX20YCSABKAESJQoHdGFyZ2V0cxgKIAMoCzIULm5lZWRsZXNpbS52MS5UYXJnZXQSFAoMdGlja19yYXRlX2h6GAsgASgBEhkKEWNvbnRhY3Rfc3BhY2luZ19tGAwgASgBEhQKDG5vZGVfY2FwdHVyZRgNIAEoCCKmAQoLU2NlbmVTb3VyY2USEQoHZXhhbXBsZRgBIAEoCUgAEhQKCnNjZW5lX3RvbWwYAiABKAlIABIvCgh1cGxvYWRlZBgDIAEoCzIbLm5lZWRsZXNpbS52MS5VcGxvYWRlZFNjZW5lSAASMwoKdXBsb2FkZWQzZBgEIAEoCzIdLm5lZWRsZXNpbS52MS5VcGxvYWRlZFNjZW5lM2RIAEIICgZzb3VyY2UiQgoHU3VyZmFjZRIQCghub2RlX2lkcxgBIAMoDRISCgpub2RlX3h5el9tGAIgAygBEhEKCXRyaWFuZ2xlcxgDIAMoDSJ+ChRDcmVhdGVTZXNzaW9uUmVxdWVzdBIoCgVzY2VuZRgBIAEoCzIZLm5lZWRsZXNpbS52MS5TY2VuZVNvdXJjZRIUCgx0aWNrX3JhdGVfaHoYAiABKAESDgoGcmVjb3JkGAMgASgIEhYKDmRldmljZV9jaGFubmVsGAQgASgIInUKFUNyZWF0ZVNlc3Npb25SZXNwb25zZRIqCgdzZXNzaW9uGAEgASgLMhkubmVlZGxlc2ltLnYxLlNlc3Npb25JbmZvEhgKEGNvbnRyb2xsZXJfdG9rZW4YAiABKAkSFgoOb2JzZXJ2ZXJfdG9rZW4YAyABKAkiFQoTTGlzdFNlc3Npb25zUmVxdWVzdCJDChRMaXN0U2Vzc2lvbnNSZXNwb25zZRIrCghzZXNzaW9ucxgBIAMoCzIZLm5lZWRsZXNpbS52MS5TZXNzaW9uSW5mbyInChFHZXRTZXNzaW9uUmVxdWVzdBISCgpzZXNzaW9uX2lkGAEgASgJIikKE0Nsb3NlU2Vzc2lvblJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCSIWChRDbG9zZVNlc3Npb25SZXNwb25zZSLRAgoLU2Vzc2lvbkluZm8SEgoKc2Vzc2lvbl9pZBgBIAEoCRISCgpzY2VuZV9uYW1lGAIgASgJEg8KB25fbm9kZXMYAyABKA0SEwoLbl90cmlhbmdsZXMYBCABKA0SFAoMdGlja19yYXRlX2h6GAUgASgBEhcKD2NyZWF0ZWRfdW5peF9tcxgGIAEoBBIMCgR0aWNrGAcgASgEEhMKC25fb2JzZXJ2ZXJzGAggASgNEhEKCXJlY29yZGluZxgJIAEoCRIUCgx0YXJnZXRfbmFtZXMYCiADKAkSGwoTZGV2aWNlX2NoYW5uZWxfcGF0aBgLIAEoCRIUCgxkZXZpY2Vfc3RhbGUYDCABKAgSHQoVZGV2aWNlX2NoYW5uZWxfYnJva2VuGA0gASgIEhEKCWRpbWVuc2lvbhgOIAEoDRIUCgxuX3RldHJhaGVkcmEYDyABKA0igAQKDFNlc3Npb25TdGF0cxINCgV0aWNrcxgBIAEoBBIWCg5jb21wdXRlX3A1MF91cxgCIAEoARIWCg5jb21wdXRlX3A5OV91cxgDIAEoARIXCg9jb21wdXRlX3A5OTlfdXMYBCABKAESFgoOY29tcHV0ZV9tYXhfdXMYBSABKAESFwoPbGF0ZW5lc3NfcDUwX3VzGAYgASgBEhcKD2xhdGVuZXNzX3A5OV91cxgHIAEoARIYChBsYXRlbmVzc19wOTk5X3VzGAggASgBEhgKEG1pc3NlZF9kZWFkbGluZXMYCSABKAQSGAoQc3VwZXJzZWRlZF9wb3NlcxgKIAEoBBIXCg9kcm9wcGVkX3JlY29yZHMYCyABKAQSFQoNY29sdW1uX21pc3NlcxgMIAEoBBIWCg5yZWplY3RlZF9wb3NlcxgNIAEoBBIVCg1jbGFtcGVkX3RpY2tzGA4gASgEEhgKEGNvbHVtbl9kZWZlcnJhbHMYDyABKAQSFwoPY29sdW1uc19ldmljdGVkGBAgASgEEh4KFmJ1ZGdldF9leGhhdXN0ZWRfdGlja3MYESABKAQSFQoNaHlicmlkX2NoZWNrcxgSIAEoBBIXCg9oeWJyaWRfcmVidWlsZHMYEyABKAQSDwoHZmF1bHRlZBgUIAEoCBINCgVmYXVsdBgVIAEoCSJMChBGbGlwQmV2ZWxSZXF1ZXN0EhIKCnNlc3Npb25faWQYASABKAkSEQoJY2xpZW50X2lkGAIgASgJEhEKCXRha2Vfb3ZlchgDIAEoCCIsChFGbGlwQmV2ZWxSZXNwb25zZRIXCg9mbGlwc19yZXF1ZXN0ZWQYASABKAQikwEKDkNvbnRyb2xSZXF1ZXN0EhIKCnNlc3Npb25faWQYASABKAkSIQoEYmFzZRgCIAEoCzITLm5lZWRsZXNpbS52MS5Qb3NlMhIWCg5jbGllbnRfdGltZV9ucxgDIAEoBBILCgNzZXEYBCABKAQSEgoKZmxpcF9iZXZlbBgFIAEoCBIRCgl0YWtlX292ZXIYBiABKAgigQEKD0NvbnRyb2xSZXF1ZXN0MxISCgpzZXNzaW9uX2lkGAEgASgJEiIKBWJhc2UzGAIgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UzEhYKDmNsaWVudF90aW1lX25zGAMgASgEEgsKA3NlcRgEIAEoBBIRCgl0YWtlX292ZXIYBSABKAgibQoOU2V0UG9zZVJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCRIhCgRiYXNlGAIgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEhEKCWNsaWVudF9pZBgDIAEoCRIRCgl0YWtlX292ZXIYBCABKAgibwoPU2V0UG9zZVJlcXVlc3QzEhIKCnNlc3Npb25faWQYASABKAkSIgoFYmFzZTMYAiABKAsyEy5uZWVkbGVzaW0udjEuUG9zZTMSEQoJY2xpZW50X2lkGAMgASgJEhEKCXRha2Vfb3ZlchgEIAEoCCLqAwoPQ29udHJvbFJlc3BvbnNlEgwKBHRpY2sYASABKAQSDgoGdGltZV9zGAIgASgBEiMKB2ZvcmNlX24YAyABKAsyEi5uZWVkbGVzaW0udjEuVmVjMhIRCgl0b3JxdWVfbm0YBCABKAESFQoNZm9yY2VfYXhpYWxfbhgFIAEoARIXCg9mb3JjZV9sYXRlcmFsX24YBiABKAESIQoEYmFzZRgHIAEoCzITLm5lZWRsZXNpbS52MS5Qb3NlMhIhCgV0aXBfbRgIIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhkKEWluc2VydGVkX2xlbmd0aF9tGAkgASgBEg8KB25fc3R1Y2sYCiABKA0SEgoKbl9zbGlwcGluZxgLIAEoDRINCgVuX3RpcBgMIAEoDRIQCghwb3NlX3NlcRgNIAEoBBIWCg5jbGllbnRfdGltZV9ucxgOIAEoBBIRCglzdGlmZm5lc3MYDyADKAESKgoObmVlZGxlX3NoYXBlX20YECADKAsyEi5uZWVkbGVzaW0udjEuVmVjMhISCgpiZXZlbF9zaWRlGBEgASgBEg8KB2ZhdWx0ZWQYFCABKAgSDQoFZmF1bHQYFSABKAkSHwoCZDMYFiABKAsyEy5uZWVkbGVzaW0udjEuVGljazMiqAEKCENvbnRhY3QzEiYKBXN0YXRlGAEgASgOMhcubmVlZGxlc2ltLnYxLk5vZGVTdGF0ZRImCgpwb3NpdGlvbl9tGAIgASgLMhIubmVlZGxlc2ltLnYxLlZlYzMSJwoLcmVmZXJlbmNlX20YAyABKAsyEi5uZWVkbGVzaW0udjEuVmVjMxIjCgdmb3JjZV9uGAQgASgLMhIubmVlZGxlc2ltLnYxLlZlYzMihQEKDFRhcmdldFNwaGVyZRIMCgRuYW1lGAEgASgJEiQKCGNlbnRlcl9tGAIgASgLMhIubmVlZGxlc2ltLnYxLlZlYzMSEAoIcmFkaXVzX20YAyABKAESEgoKZGlzdGFuY2VfbRgEIAEoARILCgNoaXQYBSABKAgSDgoGbWlzc2VkGAYgASgIIsYCCgVUaWNrMxIhCgRiYXNlGAEgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UzEiMKB2ZvcmNlX24YAiABKAsyEi5uZWVkbGVzaW0udjEuVmVjMxIlCgl0b3JxdWVfbm0YAyABKAsyEi5uZWVkbGVzaW0udjEuVmVjMxIVCg1heGlhbF9mb3JjZV9uGAQgASgBEiEKBXRpcF9tGAUgASgLMhIubmVlZGxlc2ltLnYxLlZlYzMSKgoObmVlZGxlX3NoYXBlX20YBiADKAsyEi5uZWVkbGVzaW0udjEuVmVjMxIoCghjb250YWN0cxgHIAMoCzIWLm5lZWRsZXNpbS52MS5Db250YWN0MxIrCgd0YXJnZXRzGAggAygLMhoubmVlZGxlc2ltLnYxLlRhcmdldFNwaGVyZRIRCglzdGlmZm5lc3MYCSADKAEiVAoOT2JzZXJ2ZVJlcXVlc3QSEgoKc2Vzc2lvbl9pZBgBIAEoCRIPCgdyYXRlX2h6GAIgASgBEh0KFWluY2x1ZGVfZGlzcGxhY2VtZW50cxgDIAEoCCKnAQoKTmVlZGxlTm9kZRIMCgRub2RlGAEgASgNEiYKBXN0YXRlGAIgASgOMhcubmVlZGxlc2ltLnYxLk5vZGVTdGF0ZRImCgpwb3NpdGlvbl9tGAMgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISIwoHZm9yY2VfbhgEIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhYKDm1hdGVyaWFsX3BvaW50GAUgASgIImQKC1RhcmdldFN0YXRlEgwKBG5hbWUYASABKAkSJgoKcG9zaXRpb25fbRgCIAEoCzISLm5lZWRsZXNpbS52MS5WZWMyEhIKCmRpc3RhbmNlX20YAyABKAESCwoDaGl0GAQgASgIIsUECgVGcmFtZRIMCgR0aWNrGAEgASgEEg4KBnRpbWVfcxgCIAEoARIhCgRiYXNlGAMgASgLMhMubmVlZGxlc2ltLnYxLlBvc2UyEiMKB2ZvcmNlX24YBCABKAsyEi5uZWVkbGVzaW0udjEuVmVjMhIRCgl0b3JxdWVfbm0YBSABKAESFQoNZm9yY2VfYXhpYWxfbhgGIAEoARIXCg9mb3JjZV9sYXRlcmFsX24YByABKAESIQoFdGlwX20YCCABKAsyEi5uZWVkbGVzaW0udjEuVmVjMhIZChFpbnNlcnRlZF9sZW5ndGhfbRgJIAEoARIuCgxuZWVkbGVfbm9kZXMYCiADKAsyGC5uZWVkbGVzaW0udjEuTmVlZGxlTm9kZRIqCgd0YXJnZXRzGAsgAygLMhkubmVlZGxlc2ltLnYxLlRhcmdldFN0YXRlEhsKE25vZGVfZGlzcGxhY2VtZW50X20YDCADKAESFAoMbWlzc2VkX3RpY2tzGA0gASgEEhIKCmNvbXB1dGVfdXMYDiABKAESEQoJc3RpZmZuZXNzGA8gAygBEioKDm5lZWRsZV9zaGFwZV9tGBAgAygLMhIubmVlZGxlc2ltLnYxLlZlYzISEgoKYmV2ZWxfc2lkZRgRIAEoARIPCgdmYXVsdGVkGBQgASgIEg0KBWZhdWx0GBUgASgJEh8KAmQzGBYgASgLMhMubmVlZGxlc2ltLnYxLlRpY2szEh4KFnN1cmZhY2VfZGlzcGxhY2VtZW50X20YFyADKAEiQgoQVHJhamVjdG9yeVNhbXBsZRILCgN0X3MYASABKAESIQoEYmFzZRgCIAEoCzITLm5lZWRsZXNpbS52MS5Qb3NlMiKBAQoPU2ltdWxhdGVSZXF1ZXN0EigKBXNjZW5lGAEgASgLMhkubmVlZGxlc2ltLnYxLlNjZW5lU291cmNlEjIKCnRyYWplY3RvcnkYAiADKAsyHi5uZWVkbGVzaW0udjEuVHJhamVjdG9yeVNhbXBsZRIQCghkZWNpbWF0ZRgDIAEoDSI7ChBTaW11bGF0ZVByb2dyZXNzEhIKCnRpY2tzX2RvbmUYASABKAQSEwoLdGlja3NfdG90YWwYAiABKAQiwQIKCVNlcmllc1JvdxILCgN0X3MYASABKAESIQoEYmFzZRgCIAEoCzITLm5lZWRsZXNpbS52MS5Qb3NlMhIjCgdmb3JjZV9uGAMgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISEQoJdG9ycXVlX25tGAQgASgBEhUKDWZvcmNlX2F4aWFsX24YBSABKAESFwoPZm9yY2VfbGF0ZXJhbF9uGAYgASgBEiEKBXRpcF9tGAcgASgLMhIubmVlZGxlc2ltLnYxLlZlYzISGQoRaW5zZXJ0ZWRfbGVuZ3RoX20YCCABKAESDwoHbl9zdHVjaxgJIAEoDRISCgpuX3NsaXBwaW5nGAogASgNEg0KBW5fdGlwGAsgASgNEioKB3RhcmdldHMYDCADKAsyGS5uZWVkbGVzaW0udjEuVGFyZ2V0U3RhdGUiNAoLU2VyaWVzQ2h1bmsSJQoEcm93cxgBIAMoCzIXLm5lZWRsZXNpbS52MS5TZXJpZXNSb3cingEKDlNpbXVsYXRlUmVzdWx0EiUKBHJvd3MYASADKAsyFy5uZWVkbGVzaW0udjEuU2VyaWVzUm93Eg0KBXRpY2tzGAIgASgEEg4KBndhbGxfcxgDIAEoARITCgtzdGVwX3A1MF91cxgEIAEoARITCgtzdGVwX3A5OV91cxgFIAEoARIcChRmaW5hbF9kaXNwbGFjZW1lbnRfbRgGIAMoASKsAQoQU2ltdWxhdGVSZXNwb25zZRIyCghwcm9ncmVzcxgBIAEoCzIeLm5lZWRsZXNpbS52MS5TaW11bGF0ZVByb2dyZXNzSAASLgoGcmVzdWx0GAIgASgLMhwubmVlZGxlc2ltLnYxLlNpbXVsYXRlUmVzdWx0SAASKwoGc2VyaWVzGAMgASgLMhkubmVlZGxlc2ltLnYxLlNlcmllc0NodW5rSABCBwoFZXZlbnQiSgoVU3RhcnRSZWNvcmRpbmdSZXF1ZXN0EhIKCnNlc3Npb25faWQYASABKAkSHQoVaW5jbHVkZV9kaXNwbGFjZW1lbnRzGAIgASgIIioKFFN0b3BSZWNvcmRpbmdSZXF1ZXN0EhIKCnNlc3Npb25faWQYASABKAkiaQoNUmVjb3JkaW5nSW5mbxIMCgRuYW1lGAEgASgJEhIKCnNlc3Npb25faWQYAiABKAkSEgoKc2l6ZV9ieXRlcxgDIAEoBBIQCghtZXNzYWdlcxgEIAEoBBIQCghmaW5pc2hlZBgFIAEoCCIXChVMaXN0UmVjb3JkaW5nc1JlcXVlc3QiSQoWTGlzdFJlY29yZGluZ3NSZXNwb25zZRIvCgpyZWNvcmRpbmdzGAEgAygLMhsubmVlZGxlc2ltLnYxLlJlY29yZGluZ0luZm8iKAoYRG93bmxvYWRSZWNvcmRpbmdSZXF1ZXN0EgwKBG5hbWUYASABKAkiLgoOUmVjb3JkaW5nQ2h1bmsSDAoEZGF0YRgBIAEoDBIOCgZvZmZzZXQYAiABKAQqagoJTm9kZVN0YXRlEhoKFk5PREVfU1RBVEVfVU5TUEVDSUZJRUQQABIUChBOT0RFX1NUQVRFX1NUVUNLEAESFwoTTk9ERV9TVEFURV9TTElQUElORxACEhIKDk5PREVfU1RBVEVfVElQEAMysQQKDlNlc3Npb25TZXJ2aWNlElgKDUNyZWF0ZVNlc3Npb24SIi5uZWVkbGVzaW0udjEuQ3JlYXRlU2Vzc2lvblJlcXVlc3QaIy5uZWVkbGVzaW0udjEuQ3JlYXRlU2Vzc2lvblJlc3BvbnNlElUKDExpc3RTZXNzaW9ucxIhLm5lZWRsZXNpbS52MS5MaXN0U2Vzc2lvbnNSZXF1ZXN0GiIubmVlZGxlc2ltLnYxLkxpc3RTZXNzaW9uc1Jlc3BvbnNlEkgKCkdldFNlc3Npb24SHy5uZWVkbGVzaW0udjEuR2V0U2Vzc2lvblJlcXVlc3QaGS5uZWVkbGVzaW0udjEuU2Vzc2lvbkluZm8SPgoHR2V0TWVzaBIfLm5lZWRsZXNpbS52MS5HZXRTZXNzaW9uUmVxdWVzdBoSLm5lZWRsZXNpbS52MS5NZXNoEkcKCEdldFN0YXRzEh8ubmVlZGxlc2ltLnYxLkdldFNlc3Npb25SZXF1ZXN0GhoubmVlZGxlc2ltLnYxLlNlc3Npb25TdGF0cxJVCgxDbG9zZVNlc3Npb24SIS5uZWVkbGVzaW0udjEuQ2xvc2VTZXNzaW9uUmVxdWVzdBoiLm5lZWRsZXNpbS52MS5DbG9zZVNlc3Npb25SZXNwb25zZRJECgpHZXRTdXJmYWNlEh8ubmVlZGxlc2ltLnYxLkdldFNlc3Npb25SZXF1ZXN0GhUubmVlZGxlc2ltLnYxLlN1cmZhY2UyigMKDkNvbnRyb2xTZXJ2aWNlEkoKB0NvbnRyb2wSHC5uZWVkbGVzaW0udjEuQ29udHJvbFJlcXVlc3QaHS5uZWVkbGVzaW0udjEuQ29udHJvbFJlc3BvbnNlKAEwARJGCgdTZXRQb3NlEhwubmVlZGxlc2ltLnYxLlNldFBvc2VSZXF1ZXN0Gh0ubmVlZGxlc2ltLnYxLkNvbnRyb2xSZXNwb25zZRJMCglGbGlwQmV2ZWwSHi5uZWVkbGVzaW0udjEuRmxpcEJldmVsUmVxdWVzdBofLm5lZWRsZXNpbS52MS5GbGlwQmV2ZWxSZXNwb25zZRJMCghDb250cm9sMxIdLm5lZWRsZXNpbS52MS5Db250cm9sUmVxdWVzdDMaHS5uZWVkbGVzaW0udjEuQ29udHJvbFJlc3BvbnNlKAEwARJICghTZXRQb3NlMxIdLm5lZWRsZXNpbS52MS5TZXRQb3NlUmVxdWVzdDMaHS5uZWVkbGVzaW0udjEuQ29udHJvbFJlc3BvbnNlMlAKDk9ic2VydmVTZXJ2aWNlEj4KB09ic2VydmUSHC5uZWVkbGVzaW0udjEuT2JzZXJ2ZVJlcXVlc3QaEy5uZWVkbGVzaW0udjEuRnJhbWUwATJgChFTaW11bGF0aW9uU2VydmljZRJLCghTaW11bGF0ZRIdLm5lZWRsZXNpbS52MS5TaW11bGF0ZVJlcXVlc3QaHi5uZWVkbGVzaW0udjEuU2ltdWxhdGVSZXNwb25zZTABMvICChBSZWNvcmRpbmdTZXJ2aWNlElIKDlN0YXJ0UmVjb3JkaW5nEiMubmVlZGxlc2ltLnYxLlN0YXJ0UmVjb3JkaW5nUmVxdWVzdBobLm5lZWRsZXNpbS52MS5SZWNvcmRpbmdJbmZvElAKDVN0b3BSZWNvcmRpbmcSIi5uZWVkbGVzaW0udjEuU3RvcFJlY29yZGluZ1JlcXVlc3QaGy5uZWVkbGVzaW0udjEuUmVjb3JkaW5nSW5mbxJbCg5MaXN0UmVjb3JkaW5ncxIjLm5lZWRsZXNpbS52MS5MaXN0UmVjb3JkaW5nc1JlcXVlc3QaJC5uZWVkbGVzaW0udjEuTGlzdFJlY29yZGluZ3NSZXNwb25zZRJbChFEb3dubG9hZFJlY29yZGluZxImLm5lZWRsZXNpbS52MS5Eb3dubG9hZFJlY29yZGluZ1JlcXVlc3QaHC5uZWVkbGVzaW0udjEuUmVjb3JkaW5nQ2h1bmswAWIGcHJvdG8z"),Ey=Xn(Pr,0);var wy=Xn(Pr,4);var Ay=Xn(Pr,6);var Ty=Xn(Pr,11);var Ry=Xn(Pr,34);var Iy=Oa(Pr,0),Cy=Oa(Pr,1),Ny=Oa(Pr,2);var Py=Oa(Pr,4);var Cc=Ad({baseUrl:window.location.origin,useBinaryFormat:!0}),ts=_o(Iy,Cc),Nc=_o(Cy,Cc),Ly=_o(Ny,Cc),Ba=_o(Py,Cc);function hi(n){return{headers:{authorization:`Bearer ${n}`}}}var hr=new Map;function et(n,e){let t=document.getElementById(n);if(!t)throw new Error(`index.html has no element #${n}`);if(e&&!(t instanceof e))throw new Error(`#${n} is a <${t.tagName.toLowerCase()}>, not a ${e.name}`);return t}function zt(n){et("status").textContent=n}function an(n,e){document.body.dataset[n]=String(e)}function vo(n){return{timeS:n.timeS,depthMm:n.insertedLengthM*1e3,axialN:n.forceAxialN,lateralN:n.forceLateralN,torqueMnm:n.torqueNm*1e3}}var Dy=["timeS","depthMm","axialN","lateralN","torqueMnm"],[Pc,Uy,ka,Va,Ga]=[0,1,2,3,4];function Oy(n){return[new Float64Array(n),new Float64Array(n),new Float64Array(n),new Float64Array(n),new Float64Array(n)]}function Fy(n,e,t){return[n[0].subarray(e,t),n[1].subarray(e,t),n[2].subarray(e,t),n[3].subarray(e,t),n[4].subarray(e,t)]}var Td=class{capacity;cols;next=0;len=0;constructor(e){if(!(Number.isInteger(e)&&e>0))throw new RangeError(`a sample ring needs a positive capacity, not ${e}`);this.capacity=e,this.cols=Oy(2*e)}get length(){return this.len}clear(){this.next=0,this.len=0}push(e){let{next:t,capacity:i}=this;Dy.forEach((r,s)=>{this.cols[s][t]=e[r],this.cols[s][t+i]=e[r]}),this.next=(t+1)%i,this.len=Math.min(this.len+1,i)}newestTimeS(){return this.len?this.cols[Pc][(this.next-1+this.capacity)%this.capacity]:null}window(e){let t=(this.next-this.len+this.capacity)%this.capacity,i=t,r=t+this.len;if(e!==null){let s=this.cols[Pc],o=r;for(;i<o;){let a=i+o>>>1;s[a]<e?i=a+1:o=a}}return Fy(this.cols,i,r)}},Rd=class{capacity;cols;len=0;hasNewest=!1;stride=1;sinceKept=0;constructor(e){if(!(Number.isInteger(e)&&e>=2&&e%2===0))throw new RangeError(`a thinned trace needs an even capacity of at least 2, not ${e}`);this.capacity=e,this.cols=Oy(e+1)}get keepsEvery(){return this.stride}clear(){this.len=0,this.hasNewest=!1,this.stride=1,this.sinceKept=0}push(e){let t=this.len===0||++this.sinceKept>=this.stride;if(t&&this.len===this.capacity){for(let i of this.cols)for(let r=0;r<this.capacity/2;r++)i[r]=i[2*r];this.len=this.capacity/2,this.stride*=2}Dy.forEach((i,r)=>{this.cols[r][this.len]=e[i]}),t?(this.len++,this.sinceKept=0,this.hasNewest=!1):this.hasNewest=!0}columns(){return Fy(this.cols,0,this.len+(this.hasNewest?1:0))}},xo=class n{recent;trace;version=0;constructor(e=4096,t=1024){this.recent=new Td(e),this.trace=new Rd(t)}static of(e){let t=new n(Math.max(1,e.length));for(let i of e)t.push(i);return t}push(e){this.recent.push(e),this.trace.push(e),this.version++}clear(){this.recent.clear(),this.trace.clear(),this.version++}};var me={session:null,mode:"live",mesh:null,dim:2,surface3:null,frame:null,framesReceived:0,streamAbort:null,history:new xo,needleLengthM:0,strainScale:.001,viewBounds:null,dirty:!0,driving:{commanded:null,pending:null,commanded3:null,pending3:null,inFlight:0,lastSentMs:0,posesCommanded:0,posesAcked:0,drag:null},playback:{frames:[],history:null,playing:!1,startedMs:0,startedSimS:0}};function By(n,e){me.mode="live",me.session={id:n,token:e},me.mesh=null,me.dim=2,me.surface3=null,me.frame=null,me.viewBounds=null,me.history.clear(),me.framesReceived=0,me.driving.commanded=null,me.driving.commanded3=null,me.dirty=!0}function za(n){let e=Float64Array.from(n.nodeXyM),t=Uint32Array.from(n.triangleNodes),i=t.length/3,r=new Float64Array(i*6),s=new Map;for(let h=0;h<i;h++){let f=t[3*h],d=t[3*h+1],p=t[3*h+2],x=e[2*f],m=e[2*f+1],g=e[2*d],v=e[2*d+1],T=e[2*p],M=e[2*p+1],R=(g-x)*(M-m)-(T-x)*(v-m),w=R!==0?1/R:0;r[6*h]=(v-M)*w,r[6*h+1]=(M-m)*w,r[6*h+2]=(m-v)*w,r[6*h+3]=(T-g)*w,r[6*h+4]=(x-T)*w,r[6*h+5]=(g-x)*w;for(let[y,A]of[[f,d],[d,p],[p,f]]){let k=y<A?`${y},${A}`:`${A},${y}`;s.set(k,(s.get(k)??0)+1)}}let o=[];for(let[h,f]of s)f===1&&o.push(...h.split(",").map(Number));let a=1/0,l=1/0,c=-1/0,u=-1/0;for(let h=0;h<e.length;h+=2)a=Math.min(a,e[h]),c=Math.max(c,e[h]),l=Math.min(l,e[h+1]),u=Math.max(u,e[h+1]);return{xy:e,tri:t,coef:r,boundary:Uint32Array.from(o),bounds:[a,l,c,u]}}function ky(n,e){let t=n.tri.length/3,i=new Float64Array(t);if(e.length<n.xy.length)return i;for(let r=0;r<t;r++){let s=0,o=0,a=0;for(let c=0;c<3;c++){let u=n.tri[3*r+c],h=n.coef[6*r+c],f=n.coef[6*r+3+c],d=e[2*u],p=e[2*u+1];s+=h*d,o+=f*p,a+=f*d+h*p}let l=.5*a;i[r]=Math.sqrt(s*s+o*o+2*l*l)}return i}var Lc=[[247,251,255],[254,224,144],[253,141,60],[215,48,31],[127,0,0]];function Id(n){let t=Math.max(0,Math.min(1,n))*(Lc.length-1),i=Math.min(Lc.length-2,Math.floor(t)),r=t-i,[s,o]=[Lc[i],Lc[i+1]],a=s.map((l,c)=>Math.round(l+r*(o[c]-l)));return`rgb(${a[0]},${a[1]},${a[2]})`}function Cd(n,e){let[t,i,r,s]=e.viewBounds??e.mesh?.bounds??[-.05,-.05,.05,.05],o=r-t||.1,a=s-i||.1,l=24,c=Math.min((n.width-2*l)/o,(n.height-2*l)/a),u=(n.width-c*o)/2-c*t,h=(n.height+c*a)/2+c*i;return{s:c,ox:u,oy:h}}var Lr=(n,e,t)=>[n.ox+n.s*e,n.oy-n.s*t];function Gy(n,e){if(!n.mesh||n.viewBounds)return;let[t,i,r,s]=n.mesh.bounds,o=[];e.base&&o.push([e.base.xM,e.base.yM]),e.tipM&&o.push([e.tipM.x,e.tipM.y]);for(let[c,u]of o)t=Math.min(t,c),r=Math.max(r,c),i=Math.min(i,u),s=Math.max(s,u);let a=.08*Math.max(r-t,s-i),l=[t-a,i-a,r+a,s+a];n.viewBounds=l}var Is={stuck:"#2166ac",slipping:"#f18f01",tip:"#e7298a",other:"#999"};function ME(n){let e=n.getContext("2d");if(!e)throw new Error("this browser gives no 2D canvas context");return e}function zy(n,e){let t=ME(n);t.setTransform(1,0,0,1,0,0),t.fillStyle="#ffffff",t.fillRect(0,0,n.width,n.height);let i=Cd(n,e),r=e.frame;if(e.mesh){let o=e.mesh,a=r?.nodeDisplacementM??[],l=a.length>=o.xy.length,c=ky(o,a),u=0;for(let d of c)u=Math.max(u,d);e.strainScale=Math.max(1e-4,u>e.strainScale?u:.98*e.strainScale+.02*u);let h=o.tri.length/3,f=new Float64Array(o.xy.length);for(let d=0;d<o.xy.length;d+=2){let p=o.xy[d]+(l?a[d]:0),x=o.xy[d+1]+(l?a[d+1]:0);f[d]=i.ox+i.s*p,f[d+1]=i.oy-i.s*x}t.lineWidth=.5,t.strokeStyle="rgba(60,60,60,0.35)";for(let d=0;d<h;d++){let p=o.tri[3*d],x=o.tri[3*d+1],m=o.tri[3*d+2];t.beginPath(),t.moveTo(f[2*p],f[2*p+1]),t.lineTo(f[2*x],f[2*x+1]),t.lineTo(f[2*m],f[2*m+1]),t.closePath(),t.fillStyle=Id(c[d]/e.strainScale),t.fill(),h<2e4&&t.stroke()}t.save(),t.setLineDash([5,4]),t.strokeStyle="#1f4e9c",t.lineWidth=1.2,t.beginPath();for(let d=0;d<o.boundary.length;d+=2){let p=o.boundary[d],x=o.boundary[d+1];t.moveTo(...Lr(i,o.xy[2*p],o.xy[2*p+1])),t.lineTo(...Lr(i,o.xy[2*x],o.xy[2*x+1]))}t.stroke(),t.restore(),EE(n,t,e.strainScale)}if(r){for(let o of r.targets){if(!o.positionM)continue;let[a,l]=Lr(i,o.positionM.x,o.positionM.y);t.beginPath(),t.arc(a,l,7,0,2*Math.PI),t.lineWidth=2.5,t.strokeStyle=o.hit?"#1a9850":"#d73027",t.fillStyle=o.hit?"rgba(26,152,80,0.6)":"rgba(215,48,39,0.12)",t.fill(),t.stroke(),t.fillStyle="#222",t.font="11px system-ui, sans-serif",t.fillText(`${o.name} ${o.hit?"hit":`${(o.distanceM*1e3).toFixed(1)} mm`}`,a+10,l-8)}if(r.base){let o=r.base;if(t.lineCap="round",t.lineJoin="round",t.strokeStyle="#333",t.lineWidth=3,t.beginPath(),r.needleShapeM.length>=2)r.needleShapeM.forEach((c,u)=>u===0?t.moveTo(...Lr(i,c.x,c.y)):t.lineTo(...Lr(i,c.x,c.y)));else{r.tipM&&(e.needleLengthM=Math.hypot(r.tipM.x-o.xM,r.tipM.y-o.yM)||e.needleLengthM);let c=o.xM+e.needleLengthM*Math.cos(o.thetaRad),u=o.yM+e.needleLengthM*Math.sin(o.thetaRad);t.moveTo(...Lr(i,o.xM,o.yM)),t.lineTo(...Lr(i,c,u))}t.stroke();let[a,l]=Lr(i,o.xM,o.yM);t.fillStyle="#333",t.fillRect(a-6,l-6,12,12)}for(let o of r.needleNodes){if(!o.positionM)continue;let[a,l]=Lr(i,o.positionM.x,o.positionM.y);t.beginPath(),t.arc(a,l,o.state===3?5:4,0,2*Math.PI),t.fillStyle=o.state===1?Is.stuck:o.state===2?Is.slipping:o.state===3?Is.tip:Is.other,t.fill()}}t.font="11px system-ui, sans-serif",[["stuck",Is.stuck],["slipping",Is.slipping],["tip",Is.tip]].forEach(([o,a],l)=>{t.fillStyle=a,t.beginPath(),t.arc(14,14+15*l,4,0,2*Math.PI),t.fill(),t.fillStyle="#222",t.fillText(o,24,18+15*l)}),e.mode==="playback"&&(t.fillStyle="#7b3294",t.fillText("PLAYBACK",n.width-70,16))}function EE(n,e,t){let i=n.width-24,r=30,s=150;for(let o=0;o<s;o++)e.fillStyle=Id(1-o/s),e.fillRect(i,r+o,12,1);e.strokeStyle="#666",e.strokeRect(i,r,12,s),e.fillStyle="#222",e.font="10px system-ui, sans-serif",e.textAlign="right",e.fillText(`strain ${t.toExponential(1)}`,i+12,r-6),e.fillText("0",i-3,r+s),e.textAlign="left"}var Nd=`web-${Date.now().toString(36)}-${Math.random().toString(36).slice(2)}`;function Hy(){let n=me.driving;if(n.commanded)return{...n.commanded};let e=me.frame?.base;return e?{xM:e.xM,yM:e.yM,thetaRad:e.thetaRad}:null}function Dc(n){let e=me.driving;e.posesCommanded++,an("posesCommanded",e.posesCommanded),an("inFlight",e.inFlight),e.commanded=n,e.pending=n,Uc()}function Wy(n){let e=me.driving;e.posesCommanded++,an("posesCommanded",e.posesCommanded),e.commanded3=n,e.pending3=n,Uc()}function wE(n,e){let t=me.driving,i=hi(e);if(t.pending3){let r=t.pending3;t.pending3=null;let[s,o,a,l]=r.quaternion,[c,u,h]=r.positionM,f=yn(wy,{positionM:{x:c,y:u,z:h},orientation:{w:s,x:o,y:a,z:l}});return()=>Nc.setPose3({sessionId:n,base3:f,clientId:Nd},i)}if(t.pending){let r=t.pending;t.pending=null;let s=yn(Ey,{xM:r.xM,yM:r.yM,thetaRad:r.thetaRad});return()=>Nc.setPose({sessionId:n,base:s,clientId:Nd},i)}return null}function Uc(){let n=me.driving,e=me.session;if(!(n.pending||n.pending3)||!e||n.inFlight>=2)return;let t=performance.now();if(t-n.lastSentMs<10){setTimeout(Uc,10-(t-n.lastSentMs));return}let i=wE(e.id,e.token);i&&(n.lastSentMs=t,n.inFlight++,i().then(()=>{n.posesAcked++,an("poses",n.posesAcked)}).catch(r=>zt(`SetPose: ${String(r)}`)).finally(()=>{n.inFlight--,Uc()}))}function Xy(n){n.addEventListener("mousedown",e=>{if(me.mode!=="live"||me.dim!==2)return;let t=Hy();if(!t)return;let i=n.getBoundingClientRect(),r=n.width/i.width/Cd(n,me).s;me.driving.drag={start:t,clientX:e.clientX,clientY:e.clientY,mPerClientPx:r,free:e.altKey,rotate:e.shiftKey},e.preventDefault()}),window.addEventListener("mousemove",e=>{let t=me.driving.drag;if(!t)return;let i=(e.clientX-t.clientX)*t.mPerClientPx,r=-(e.clientY-t.clientY)*t.mPerClientPx,s=t.start;if(t.rotate)Dc({...s,thetaRad:s.thetaRad+(e.clientX-t.clientX)*.005});else if(t.free)Dc({...s,xM:s.xM+i,yM:s.yM+r});else{let o=Math.cos(s.thetaRad),a=Math.sin(s.thetaRad),l=i*o+r*a;Dc({...s,xM:s.xM+l*o,yM:s.yM+l*a})}}),window.addEventListener("mouseup",()=>{me.driving.drag=null}),n.addEventListener("wheel",e=>{if(me.mode!=="live"||me.dim!==2)return;let t=Hy();t&&(e.preventDefault(),Dc({...t,thetaRad:t.thetaRad-Math.sign(e.deltaY)*.01}))},{passive:!1})}async function Yy(){let n=me.session;if(!n)return zt("watch a session first");try{let e=await Nc.flipBevel({sessionId:n.id,clientId:Nd},hi(n.token));zt(`bevel flip ${e.flipsRequested} requested`)}catch(e){zt(`FlipBevel: ${String(e)}`)}}var AE="uplot",TE="u-hz",RE="u-vt",IE="u-title",CE="u-wrap",NE="u-under",PE="u-over",LE="u-axis",Ps="u-off",DE="u-select",UE="u-cursor-x",OE="u-cursor-y",FE="u-cursor-pt",BE="u-legend",kE="u-live",VE="u-inline",GE="u-series",zE="u-marker",Zy="u-label",HE="u-value",Wa="width",Xa="height";var Ky="bottom",bo="left",Pd="right",$d="#000",$y=$d+"0",Ld="mousemove",qy="mousedown",Dd="mouseup",Jy="mouseenter",jy="mouseleave",Qy="dblclick",WE="resize",XE="scroll",e_="change",Vc="dppxchange",qd="--",Ro=typeof window<"u",kd=Ro?document:null,Mo=Ro?window:null,YE=Ro?navigator:null,At,Oc;function Vd(){let n=devicePixelRatio;At!=n&&(At=n,Oc&&zd(e_,Oc,Vd),Oc=matchMedia(`(min-resolution: ${At-.001}dppx) and (max-resolution: ${At+.001}dppx)`),Ls(e_,Oc,Vd),Mo.dispatchEvent(new CustomEvent(Vc)))}function xi(n,e){if(e!=null){let t=n.classList;!t.contains(e)&&t.add(e)}}function Gd(n,e){let t=n.classList;t.contains(e)&&t.remove(e)}function Kt(n,e,t){n.style[e]=t+"px"}function Yi(n,e,t,i){let r=kd.createElement(n);return e!=null&&xi(r,e),t?.insertBefore(r,i),r}function Ni(n,e){return Yi("div",n,e)}var t_=new WeakMap;function fr(n,e,t,i,r){let s="translate("+e+"px,"+t+"px)",o=t_.get(n);s!=o&&(n.style.transform=s,t_.set(n,s),e<0||t<0||e>i||t>r?xi(n,Ps):Gd(n,Ps))}var n_=new WeakMap;function i_(n,e,t){let i=e+t,r=n_.get(n);i!=r&&(n_.set(n,i),n.style.background=e,n.style.borderColor=t)}var r_=new WeakMap;function s_(n,e,t,i){let r=e+""+t,s=r_.get(n);r!=s&&(r_.set(n,r),n.style.height=t+"px",n.style.width=e+"px",n.style.marginLeft=i?-e/2+"px":0,n.style.marginTop=i?-t/2+"px":0)}var Jd={passive:!0},ZE={...Jd,capture:!0};function Ls(n,e,t,i){e.addEventListener(n,t,i?ZE:Jd)}function zd(n,e,t,i){e.removeEventListener(n,t,Jd)}Ro&&Vd();function Zi(n,e,t,i){let r;t=t||0,i=i||e.length-1;let s=i<=2147483647;for(;i-t>1;)r=s?t+i>>1:vi((t+i)/2),e[r]<n?t=r:i=r;return n-e[t]<=e[i]-n?t:i}function L_(n){return(t,i,r)=>{let s=-1,o=-1;for(let a=i;a<=r;a++)if(n(t[a])){s=a;break}for(let a=r;a>=i;a--)if(n(t[a])){o=a;break}return[s,o]}}var D_=n=>n!=null,U_=n=>n!=null&&n>0,Hc=L_(D_),KE=L_(U_);function $E(n,e,t,i=0,r=!1){let s=r?KE:Hc,o=r?U_:D_;[e,t]=s(n,e,t);let a=n[e],l=n[e];if(e>-1)if(i==1)a=n[e],l=n[t];else if(i==-1)a=n[t],l=n[e];else for(let c=e;c<=t;c++){let u=n[c];o(u)&&(u<a?a=u:u>l&&(l=u))}return[a??kt,l??-kt]}function Wc(n,e,t,i){let r=l_(n),s=l_(e);n==e&&(r==-1?(n*=t,e/=t):(n/=t,e*=t));let o=t==10?Dr:O_,a=r==1?vi:Pi,l=s==1?Pi:vi,c=a(o(Tn(n))),u=l(o(Tn(e))),h=Eo(t,c),f=Eo(t,u);return t==10&&(c<0&&(h=Vt(h,-c)),u<0&&(f=Vt(f,-u))),i||t==2?(n=h*r,e=f*s):(n=V_(n,h),e=Xc(e,f)),[n,e]}function jd(n,e,t,i){let r=Wc(n,e,t,i);return n==0&&(r[0]=0),e==0&&(r[1]=0),r}var Qd=.1,o_={mode:3,pad:Qd},Za={pad:0,soft:null,mode:0},qE={min:Za,max:Za};function Gc(n,e,t,i){return Yc(t)?a_(n,e,t):(Za.pad=t,Za.soft=i?0:null,Za.mode=i?3:0,a_(n,e,qE))}function Et(n,e){return n??e}function JE(n,e,t){for(e=Et(e,0),t=Et(t,n.length-1);e<=t;){if(n[e]!=null)return!0;e++}return!1}function a_(n,e,t){let i=t.min,r=t.max,s=Et(i.pad,0),o=Et(r.pad,0),a=Et(i.hard,-kt),l=Et(r.hard,kt),c=Et(i.soft,kt),u=Et(r.soft,-kt),h=Et(i.mode,0),f=Et(r.mode,0),d=e-n,p=Dr(d),x=ri(Tn(n),Tn(e)),m=Dr(x),g=Tn(m-p);(d<1e-24||g>10)&&(d=0,(n==0||e==0)&&(d=1e-24,h==2&&c!=kt&&(s=0),f==2&&u!=-kt&&(o=0)));let v=d||x||1e3,T=Dr(v),M=Eo(10,vi(T)),R=v*(d==0?n==0?.1:1:s),w=Vt(V_(n-R,M/10),24),y=n>=c&&(h==1||h==3&&w<=c||h==2&&w>=c)?c:kt,A=ri(a,w<y&&n>=y?y:Ki(y,w)),k=v*(d==0?e==0?.1:1:o),D=Vt(Xc(e+k,M/10),24),L=e<=u&&(f==1||f==3&&D>=u||f==2&&D<=u)?u:-kt,H=Ki(l,D>L&&e<=L?L:ri(L,D));return A==H&&A==0&&(H=100),[A,H]}var jE=new Intl.NumberFormat(Ro?YE.language:"en-US"),ep=n=>jE.format(n),bi=Math,kc=bi.PI,Tn=bi.abs,vi=bi.floor,An=bi.round,Pi=bi.ceil,Ki=bi.min,ri=bi.max,Eo=bi.pow,l_=bi.sign,Dr=bi.log10,O_=bi.log2,QE=(n,e=1)=>bi.sinh(n)*e,Ud=(n,e=1)=>bi.asinh(n/e),kt=1/0;function c_(n){return(Dr((n^n>>31)-(n>>31))|0)+1}function Hd(n,e,t){return Ki(ri(n,e),t)}function F_(n){return typeof n=="function"}function xt(n){return F_(n)?n:()=>n}var ew=()=>{},B_=n=>n,k_=(n,e)=>e,tw=n=>null,u_=n=>!0,h_=(n,e)=>n==e,nw=/\.\d*?(?=9{6,}|0{6,})/gm,Ds=n=>{if(z_(n)||is.has(n))return n;let e=`${n}`,t=e.match(nw);if(t==null)return n;let i=t[0].length-1;if(e.indexOf("e-")!=-1){let[r,s]=e.split("e");return+`${Ds(r)}e${s}`}return Vt(n,i)};function Cs(n,e){return Ds(Vt(Ds(n/e))*e)}function Xc(n,e){return Ds(Pi(Ds(n/e))*e)}function V_(n,e){return Ds(vi(Ds(n/e))*e)}function Vt(n,e=0){if(z_(n))return n;let t=10**e,i=n*t*(1+Number.EPSILON);return An(i)/t}var is=new Map;function G_(n){return((""+n).split(".")[1]||"").length}function $a(n,e,t,i){let r=[],s=i.map(G_);for(let o=e;o<t;o++){let a=Tn(o),l=Vt(Eo(n,o),a);for(let c=0;c<i.length;c++){let u=n==10?+`${i[c]}e${o}`:i[c]*l,h=(o>=0?0:a)+(o>=s[c]?0:s[c]),f=n==10?u:Vt(u,h);r.push(f),is.set(f,h)}}return r}var Ka={},tp=[],wo=[null,null],ns=Array.isArray,z_=Number.isInteger,iw=n=>n===void 0;function f_(n){return typeof n=="string"}function Yc(n){let e=!1;if(n!=null){let t=n.constructor;e=t==null||t==Object}return e}function rw(n){return n!=null&&typeof n=="object"}var sw=Object.getPrototypeOf(Uint8Array),H_="__proto__";function Ao(n,e=Yc){let t;if(ns(n)){let i=n.find(r=>r!=null);if(ns(i)||e(i)){t=Array(n.length);for(let r=0;r<n.length;r++)t[r]=Ao(n[r],e)}else t=n.slice()}else if(n instanceof sw)t=n.slice();else if(e(n)){t={};for(let i in n)i!=H_&&(t[i]=Ao(n[i],e))}else t=n;return t}function vn(n){let e=arguments;for(let t=1;t<e.length;t++){let i=e[t];for(let r in i)r!=H_&&(Yc(n[r])?vn(n[r],Ao(i[r])):n[r]=Ao(i[r]))}return n}var ow=0,aw=1,lw=2;function cw(n,e,t){for(let i=0,r,s=-1;i<e.length;i++){let o=e[i];if(o>s){for(r=o-1;r>=0&&n[r]==null;)n[r--]=null;for(r=o+1;r<t&&n[r]==null;)n[s=r++]=null}}}function uw(n,e){if(dw(n)){let o=n[0].slice();for(let a=1;a<n.length;a++)o.push(...n[a].slice(1));return pw(o[0])||(o=fw(o)),o}let t=new Set;for(let o=0;o<n.length;o++){let l=n[o][0],c=l.length;for(let u=0;u<c;u++)t.add(l[u])}let i=[Array.from(t).sort((o,a)=>o-a)],r=i[0].length,s=new Map;for(let o=0;o<r;o++)s.set(i[0][o],o);for(let o=0;o<n.length;o++){let a=n[o],l=a[0];for(let c=1;c<a.length;c++){let u=a[c],h=Array(r).fill(void 0),f=e?e[o][c]:aw,d=[];for(let p=0;p<u.length;p++){let x=u[p],m=s.get(l[p]);x===null?f!=ow&&(h[m]=x,f==lw&&d.push(m)):h[m]=x}cw(h,d,r),i.push(h)}}return i}var hw=typeof queueMicrotask>"u"?n=>Promise.resolve().then(n):queueMicrotask;function fw(n){let e=n[0],t=e.length,i=Array(t);for(let s=0;s<i.length;s++)i[s]=s;i.sort((s,o)=>e[s]-e[o]);let r=[];for(let s=0;s<n.length;s++){let o=n[s],a=Array(t);for(let l=0;l<t;l++)a[l]=o[i[l]];r.push(a)}return r}function dw(n){let e=n[0][0],t=e.length;for(let i=1;i<n.length;i++){let r=n[i][0];if(r.length!=t)return!1;if(r!=e){for(let s=0;s<t;s++)if(r[s]!=e[s])return!1}}return!0}function pw(n,e=100){let t=n.length;if(t<=1)return!0;let i=0,r=t-1;for(;i<=r&&n[i]==null;)i++;for(;r>=i&&n[r]==null;)r--;if(r<=i)return!0;let s=ri(1,vi((r-i+1)/e));for(let o=n[i],a=i+s;a<=r;a+=s){let l=n[a];if(l!=null){if(l<=o)return!1;o=l}}return!0}var W_=["January","February","March","April","May","June","July","August","September","October","November","December"],X_=["Sunday","Monday","Tuesday","Wednesday","Thursday","Friday","Saturday"];function Y_(n){return n.slice(0,3)}var mw=X_.map(Y_),gw=W_.map(Y_),yw={MMMM:W_,MMM:gw,WWWW:X_,WWW:mw};function Ha(n){return(n<10?"0":"")+n}function _w(n){return(n<10?"00":n<100?"0":"")+n}var xw={YYYY:n=>n.getFullYear(),YY:n=>(n.getFullYear()+"").slice(2),MMMM:(n,e)=>e.MMMM[n.getMonth()],MMM:(n,e)=>e.MMM[n.getMonth()],MM:n=>Ha(n.getMonth()+1),M:n=>n.getMonth()+1,DD:n=>Ha(n.getDate()),D:n=>n.getDate(),WWWW:(n,e)=>e.WWWW[n.getDay()],WWW:(n,e)=>e.WWW[n.getDay()],HH:n=>Ha(n.getHours()),H:n=>n.getHours(),h:n=>{let e=n.getHours();return e==0?12:e>12?e-12:e},AA:n=>n.getHours()>=12?"PM":"AM",aa:n=>n.getHours()>=12?"pm":"am",a:n=>n.getHours()>=12?"p":"a",mm:n=>Ha(n.getMinutes()),m:n=>n.getMinutes(),ss:n=>Ha(n.getSeconds()),s:n=>n.getSeconds(),fff:n=>_w(n.getMilliseconds())};function np(n,e){e=e||yw;let t=[],i=/\{([a-z]+)\}|[^{]+/gi,r;for(;r=i.exec(n);)t.push(r[0][0]=="{"?xw[r[1]]:r[0]);return s=>{let o="";for(let a=0;a<t.length;a++)o+=typeof t[a]=="string"?t[a]:t[a](s,e);return o}}var vw=new Intl.DateTimeFormat().resolvedOptions().timeZone;function bw(n,e){let t;return e=="UTC"||e=="Etc/UTC"?t=new Date(+n+n.getTimezoneOffset()*6e4):e==vw?t=n:(t=new Date(n.toLocaleString("en-US",{timeZone:e})),t.setMilliseconds(n.getMilliseconds())),t}var Z_=n=>n%1==0,zc=[1,2,2.5,5],Sw=$a(10,-32,0,zc),K_=$a(10,0,32,zc),Mw=K_.filter(Z_),Ns=Sw.concat(K_),ip=`
`,$_="{YYYY}",d_=ip+$_,q_="{M}/{D}",Ya=ip+q_,Fc=Ya+"/{YY}",J_="{aa}",Ew="{h}:{mm}",So=Ew+J_,p_=ip+So,m_=":{ss}",It=null;function j_(n){let e=n*1e3,t=e*60,i=t*60,r=i*24,s=r*30,o=r*365,l=(n==1?$a(10,0,3,zc).filter(Z_):$a(10,-3,0,zc)).concat([e,e*5,e*10,e*15,e*30,t,t*5,t*10,t*15,t*30,i,i*2,i*3,i*4,i*6,i*8,i*12,r,r*2,r*3,r*4,r*5,r*6,r*7,r*8,r*9,r*10,r*15,s,s*2,s*3,s*4,s*6,o,o*2,o*5,o*10,o*25,o*50,o*100]),c=[[o,$_,It,It,It,It,It,It,1],[r*28,"{MMM}",d_,It,It,It,It,It,1],[r,q_,d_,It,It,It,It,It,1],[i,"{h}"+J_,Fc,It,Ya,It,It,It,1],[t,So,Fc,It,Ya,It,It,It,1],[e,m_,Fc+" "+So,It,Ya+" "+So,It,p_,It,1],[n,m_+".{fff}",Fc+" "+So,It,Ya+" "+So,It,p_,It,1]];function u(h){return(f,d,p,x,m,g)=>{let v=[],T=m>=o,M=m>=s&&m<o,R=h(p),w=Vt(R*n,3),y=Od(R.getFullYear(),T?0:R.getMonth(),M||T?1:R.getDate()),A=Vt(y*n,3);if(M||T){let k=M?m/s:0,D=T?m/o:0,L=w==A?w:Vt(Od(y.getFullYear()+D,y.getMonth()+k,1)*n,3),H=new Date(An(L/n)),z=H.getFullYear(),N=H.getMonth();for(let F=0;L<=x;F++){let Z=Od(z+D*F,N+k*F,1),V=Z-h(Vt(Z*n,3));L=Vt((+Z+V)*n,3),L<=x&&v.push(L)}}else{let k=m>=r?r:m,D=vi(p)-vi(w),L=A+D+Xc(w-A,k);v.push(L);let H=h(L),z=H.getHours()+H.getMinutes()/t+H.getSeconds()/i,N=m/i,F=f.axes[d]._space,Z=g/F;for(;L=Vt(L+m,n==1?0:3),!(L>x);)if(N>1){let V=vi(Vt(z+N,6))%24,Q=h(L).getHours()-V;Q>1&&(Q=-1),L-=Q*i,z=(z+N)%24;let ie=v[v.length-1];Vt((L-ie)/m,3)*Z>=.7&&v.push(L)}else v.push(L)}return v}}return[l,c,u]}var[ww,Aw,Tw]=j_(1),[Rw,Iw,Cw]=j_(.001);$a(2,-53,53,[1]);function g_(n,e){return n.map(t=>t.map((i,r)=>r==0||r==8||i==null?i:e(r==1||t[8]==0?i:t[1]+i)))}function y_(n,e){return(t,i,r,s,o)=>{let a=e.find(p=>o>=p[0])||e[e.length-1],l,c,u,h,f,d;return i.map(p=>{let x=n(p),m=x.getFullYear(),g=x.getMonth(),v=x.getDate(),T=x.getHours(),M=x.getMinutes(),R=x.getSeconds(),w=m!=l&&a[2]||g!=c&&a[3]||v!=u&&a[4]||T!=h&&a[5]||M!=f&&a[6]||R!=d&&a[7]||a[1];return l=m,c=g,u=v,h=T,f=M,d=R,w(x)})}}function Nw(n,e){let t=np(e);return(i,r,s,o,a)=>r.map(l=>t(n(l)))}function Od(n,e,t){return new Date(n,e,t)}function __(n,e){return e(n)}var Pw="{YYYY}-{MM}-{DD} {h}:{mm}{aa}";function x_(n,e){return(t,i,r,s)=>s==null?qd:e(n(i))}function Lw(n,e){let t=n.series[e];return t.width?t.stroke(n,e):t.points.width?t.points.stroke(n,e):null}function Dw(n,e){return n.series[e].fill(n,e)}var Uw={show:!0,live:!0,isolate:!1,mount:ew,markers:{show:!0,width:2,stroke:Lw,fill:Dw,dash:"solid"},idx:null,idxs:null,values:[]};function Ow(n,e){let t=n.cursor.points,i=Ni(),r=t.size(n,e);Kt(i,Wa,r),Kt(i,Xa,r);let s=r/-2;Kt(i,"marginLeft",s),Kt(i,"marginTop",s);let o=t.width(n,e,r);return o&&Kt(i,"borderWidth",o),i}function Fw(n,e){let t=n.series[e].points;return t._fill||t._stroke}function Bw(n,e){let t=n.series[e].points;return t._stroke||t._fill}function kw(n,e){return n.series[e].points.size}var Fd=[0,0];function Vw(n,e,t){return Fd[0]=e,Fd[1]=t,Fd}function Bc(n,e,t,i=!0){return r=>{r.button==0&&(!i||r.target==e)&&t(r)}}function Bd(n,e,t,i=!0){return r=>{(!i||r.target==e)&&t(r)}}var Gw={show:!0,x:!0,y:!0,lock:!1,move:Vw,points:{one:!1,show:Ow,size:kw,width:0,stroke:Bw,fill:Fw},bind:{mousedown:Bc,mouseup:Bc,click:Bc,dblclick:Bc,mousemove:Bd,mouseleave:Bd,mouseenter:Bd},drag:{setScale:!0,x:!0,y:!1,dist:0,uni:null,click:(n,e)=>{e.stopPropagation(),e.stopImmediatePropagation()},_x:!1,_y:!1},focus:{dist:(n,e,t,i,r)=>i-r,prox:-1,bias:0},hover:{skip:[void 0],prox:null,bias:0},left:-10,top:-10,idx:null,dataIdx:null,idxs:null,event:null},Q_={show:!0,stroke:"rgba(0,0,0,0.07)",width:2},rp=vn({},Q_,{filter:k_}),ex=vn({},rp,{size:10}),tx=vn({},Q_,{show:!1}),sp='12px system-ui, -apple-system, "Segoe UI", Roboto, "Helvetica Neue", Arial, "Noto Sans", sans-serif, "Apple Color Emoji", "Segoe UI Emoji", "Segoe UI Symbol", "Noto Color Emoji"',nx="bold "+sp,ix=1.5,v_={show:!0,scale:"x",stroke:$d,space:50,gap:5,alignTo:1,size:50,labelGap:0,labelSize:30,labelFont:nx,side:2,grid:rp,ticks:ex,border:tx,font:sp,lineGap:ix,rotate:0},zw="Value",Hw="Time",b_={show:!0,scale:"x",auto:!1,sorted:1,min:kt,max:-kt,idxs:[]};function Ww(n,e,t,i,r){return e.map(s=>s==null?"":ep(s))}function Xw(n,e,t,i,r,s,o){let a=[],l=is.get(r)||0;t=o?t:Vt(Xc(t,r),l);for(let c=t;c<=i;c=Vt(c+r,l))a.push(Object.is(c,-0)?0:c);return a}function Wd(n,e,t,i,r,s,o){let a=[],l=n.scales[n.axes[e].scale].log,c=l==10?Dr:O_,u=vi(c(t));r=Eo(l,u),l==10&&(r=Ns[Zi(r,Ns)]);let h=t,f=r*l;l==10&&(f=Ns[Zi(f,Ns)]);do a.push(h),h=h+r,l==10&&!is.has(h)&&(h=Vt(h,is.get(r))),h>=f&&(r=h,f=r*l,l==10&&(f=Ns[Zi(f,Ns)]));while(h<=i);return a}function Yw(n,e,t,i,r,s,o){let l=n.scales[n.axes[e].scale].asinh,c=i>l?Wd(n,e,ri(l,t),i,r):[l],u=i>=0&&t<=0?[0]:[];return(t<-l?Wd(n,e,ri(l,-i),-t,r):[l]).reverse().map(f=>-f).concat(u,c)}var rx=/./,Zw=/[12357]/,Kw=/[125]/,S_=/1/,Xd=(n,e,t,i)=>n.map((r,s)=>e==4&&r==0||s%i==0&&t.test(r.toExponential()[r<0?1:0])?r:null);function $w(n,e,t,i,r){let s=n.axes[t],o=s.scale,a=n.scales[o],l=n.valToPos,c=s._space,u=l(10,o),h=l(9,o)-u>=c?rx:l(7,o)-u>=c?Zw:l(5,o)-u>=c?Kw:S_;if(h==S_){let f=Tn(l(1,o)-u);if(f<c)return Xd(e.slice().reverse(),a.distr,h,Pi(c/f)).reverse()}return Xd(e,a.distr,h,1)}function qw(n,e,t,i,r){let s=n.axes[t],o=s.scale,a=s._space,l=n.valToPos,c=Tn(l(1,o)-l(2,o));return c<a?Xd(e.slice().reverse(),3,rx,Pi(a/c)).reverse():e}function Jw(n,e,t,i){return i==null?qd:e==null?"":ep(e)}var M_={show:!0,scale:"y",stroke:$d,space:30,gap:5,alignTo:1,size:50,labelGap:0,labelSize:30,labelFont:nx,side:3,grid:rp,ticks:ex,border:tx,font:sp,lineGap:ix,rotate:0};function jw(n,e){let t=3+(n||1)*2;return Vt(t*e,3)}function Qw(n,e){let{scale:t,idxs:i}=n.series[0],r=n._data[0],s=n.valToPos(r[i[0]],t,!0),o=n.valToPos(r[i[1]],t,!0),a=Tn(o-s),l=n.series[e],c=a/(l.points.space*At);return i[1]-i[0]<=c}var E_={scale:null,auto:!0,sorted:0,min:kt,max:-kt},sx=(n,e,t,i,r)=>r,w_={show:!0,auto:!0,sorted:0,gaps:sx,alpha:1,facets:[vn({},E_,{scale:"x"}),vn({},E_,{scale:"y"})]},A_={scale:"y",auto:!0,sorted:0,show:!0,spanGaps:!1,gaps:sx,alpha:1,points:{show:Qw,filter:null},values:null,min:kt,max:-kt,idxs:[],path:null,clip:null};function eA(n,e,t,i,r){return t/10}var ox={time:!0,auto:!0,distr:1,log:10,asinh:1,min:null,max:null,dir:1,ori:0},tA=vn({},ox,{time:!1,ori:1}),T_={};function ax(n,e){let t=T_[n];return t||(t={key:n,plots:[],sub(i){t.plots.push(i)},unsub(i){t.plots=t.plots.filter(r=>r!=i)},pub(i,r,s,o,a,l,c){for(let u=0;u<t.plots.length;u++)t.plots[u]!=r&&t.plots[u].pub(i,r,s,o,a,l,c)}},n!=null&&(T_[n]=t)),t}var To=1,Yd=2;function Us(n,e,t){let i=n.mode,r=n.series[e],s=i==2?n._data[e]:n._data,o=n.scales,a=n.bbox,l=s[0],c=i==2?s[1]:s[e],u=i==2?o[r.facets[0].scale]:o[n.series[0].scale],h=i==2?o[r.facets[1].scale]:o[r.scale],f=a.left,d=a.top,p=a.width,x=a.height,m=n.valToPosH,g=n.valToPosV;return u.ori==0?t(r,l,c,u,h,m,g,f,d,p,x,Kc,Io,qc,cx,hx):t(r,l,c,u,h,g,m,d,f,x,p,$c,Co,lp,ux,fx)}function op(n,e){let t=0,i=0,r=Et(n.bands,tp);for(let s=0;s<r.length;s++){let o=r[s];o.series[0]==e?t=o.dir:o.series[1]==e&&(o.dir==1?i|=1:i|=2)}return[t,i==1?-1:i==2?1:i==3?2:0]}function nA(n,e,t,i,r){let s=n.mode,o=n.series[e],a=s==2?o.facets[1].scale:o.scale,l=n.scales[a];return r==-1?l.min:r==1?l.max:l.distr==3?l.dir==1?l.min:l.max:0}function Ur(n,e,t,i,r,s){return Us(n,e,(o,a,l,c,u,h,f,d,p,x,m)=>{let g=o.pxRound,v=c.dir*(c.ori==0?1:-1),T=c.ori==0?Io:Co,M,R;v==1?(M=t,R=i):(M=i,R=t);let w=g(h(a[M],c,x,d)),y=g(f(l[M],u,m,p)),A=g(h(a[R],c,x,d)),k=g(f(s==1?u.max:u.min,u,m,p)),D=new Path2D(r);return T(D,A,k),T(D,w,k),T(D,w,y),D})}function Zc(n,e,t,i,r,s){let o=null;if(n.length>0){o=new Path2D;let a=e==0?qc:lp,l=t;for(let h=0;h<n.length;h++){let f=n[h];if(f[1]>f[0]){let d=f[0]-l;d>0&&a(o,l,i,d,i+s),l=f[1]}}let c=t+r-l,u=10;c>0&&a(o,l,i-u/2,c,i+s+u)}return o}function iA(n,e,t){let i=n[n.length-1];i&&i[0]==e?i[1]=t:n.push([e,t])}function ap(n,e,t,i,r,s,o){let a=[],l=n.length;for(let c=r==1?t:i;c>=t&&c<=i;c+=r)if(e[c]===null){let h=c,f=c;if(r==1)for(;++c<=i&&e[c]===null;)f=c;else for(;--c>=t&&e[c]===null;)f=c;let d=s(n[h]),p=f==h?d:s(n[f]),x=h-r;d=o<=0&&x>=0&&x<l?s(n[x]):d;let g=f+r;p=o>=0&&g>=0&&g<l?s(n[g]):p,p>=d&&a.push([d,p])}return a}function R_(n){return n==0?B_:n==1?An:e=>Cs(e,n)}function lx(n){let e=n==0?Kc:$c,t=n==0?(r,s,o,a,l,c)=>{r.arcTo(s,o,a,l,c)}:(r,s,o,a,l,c)=>{r.arcTo(o,s,l,a,c)},i=n==0?(r,s,o,a,l)=>{r.rect(s,o,a,l)}:(r,s,o,a,l)=>{r.rect(o,s,l,a)};return(r,s,o,a,l,c=0,u=0)=>{c==0&&u==0?i(r,s,o,a,l):(c=Ki(c,a/2,l/2),u=Ki(u,a/2,l/2),e(r,s+c,o),t(r,s+a,o,s+a,o+l,c),t(r,s+a,o+l,s,o+l,u),t(r,s,o+l,s,o,u),t(r,s,o,s+a,o,c),r.closePath())}}var Kc=(n,e,t)=>{n.moveTo(e,t)},$c=(n,e,t)=>{n.moveTo(t,e)},Io=(n,e,t)=>{n.lineTo(e,t)},Co=(n,e,t)=>{n.lineTo(t,e)},qc=lx(0),lp=lx(1),cx=(n,e,t,i,r,s)=>{n.arc(e,t,i,r,s)},ux=(n,e,t,i,r,s)=>{n.arc(t,e,i,r,s)},hx=(n,e,t,i,r,s,o)=>{n.bezierCurveTo(e,t,i,r,s,o)},fx=(n,e,t,i,r,s,o)=>{n.bezierCurveTo(t,e,r,i,o,s)};function dx(n){return(e,t,i,r,s)=>Us(e,t,(o,a,l,c,u,h,f,d,p,x,m)=>{let{pxRound:g,points:v}=o,T,M;c.ori==0?(T=Kc,M=cx):(T=$c,M=ux);let R=Vt(v.width*At,3),w=(v.size-v.width)/2*At,y=Vt(w*2,3),A=new Path2D,k=new Path2D,{left:D,top:L,width:H,height:z}=e.bbox;qc(k,D-y,L-y,H+y*2,z+y*2);let N=F=>{if(l[F]!=null){let Z=g(h(a[F],c,x,d)),V=g(f(l[F],u,m,p));T(A,Z+w,V),M(A,Z,V,w,0,kc*2)}};if(s)s.forEach(N);else for(let F=i;F<=r;F++)N(F);return{stroke:R>0?A:null,fill:A,clip:k,flags:To|Yd}})}function px(n){return(e,t,i,r,s,o)=>{i!=r&&(s!=i&&o!=i&&n(e,t,i),s!=r&&o!=r&&n(e,t,r),n(e,t,o))}}var rA=px(Io),sA=px(Co);function mx(n){let e=Et(n?.alignGaps,0);return(t,i,r,s)=>Us(t,i,(o,a,l,c,u,h,f,d,p,x,m)=>{[r,s]=Hc(l,r,s);let g=o.pxRound,v=z=>g(h(z,c,x,d)),T=z=>g(f(z,u,m,p)),M,R;c.ori==0?(M=Io,R=rA):(M=Co,R=sA);let w=c.dir*(c.ori==0?1:-1),y={stroke:new Path2D,fill:null,clip:null,band:null,gaps:null,flags:To},A=y.stroke,k=!1;if(s-r>=x*4){let z=he=>t.posToVal(he,c.key,!0),N=null,F=null,Z,V,le,q=v(a[w==1?r:s]),Q=v(a[r]),ie=v(a[s]),fe=z(w==1?Q+1:ie-1);for(let he=w==1?r:s;he>=r&&he<=s;he+=w){let ee=a[he],ye=(w==1?ee<fe:ee>fe)?q:v(ee),xe=l[he];ye==q?xe!=null?(V=xe,N==null?(M(A,ye,T(V)),Z=N=F=V):V<N?N=V:V>F&&(F=V)):xe===null&&(k=!0):(N!=null&&R(A,q,T(N),T(F),T(Z),T(V)),xe!=null?(V=xe,M(A,ye,T(V)),N=F=Z=V):(N=F=null,xe===null&&(k=!0)),q=ye,fe=z(q+w))}N!=null&&N!=F&&le!=q&&R(A,q,T(N),T(F),T(Z),T(V))}else for(let z=w==1?r:s;z>=r&&z<=s;z+=w){let N=l[z];N===null?k=!0:N!=null&&M(A,v(a[z]),T(N))}let[L,H]=op(t,i);if(o.fill!=null||L!=0){let z=y.fill=new Path2D(A),N=o.fillTo(t,i,o.min,o.max,L),F=T(N),Z=v(a[r]),V=v(a[s]);w==-1&&([V,Z]=[Z,V]),M(z,V,F),M(z,Z,F)}if(!o.spanGaps){let z=[];k&&z.push(...ap(a,l,r,s,w,v,e)),y.gaps=z=o.gaps(t,i,r,s,z),y.clip=Zc(z,c.ori,d,p,x,m)}return H!=0&&(y.band=H==2?[Ur(t,i,r,s,A,-1),Ur(t,i,r,s,A,1)]:Ur(t,i,r,s,A,H)),y})}function oA(n){let e=Et(n.align,1),t=Et(n.ascDesc,!1),i=Et(n.alignGaps,0),r=Et(n.extend,!1);return(s,o,a,l)=>Us(s,o,(c,u,h,f,d,p,x,m,g,v,T)=>{[a,l]=Hc(h,a,l);let M=c.pxRound,{left:R,width:w}=s.bbox,y=Q=>M(p(Q,f,v,m)),A=Q=>M(x(Q,d,T,g)),k=f.ori==0?Io:Co,D={stroke:new Path2D,fill:null,clip:null,band:null,gaps:null,flags:To},L=D.stroke,H=f.dir*(f.ori==0?1:-1),z=A(h[H==1?a:l]),N=y(u[H==1?a:l]),F=N,Z=N;r&&e==-1&&(Z=R,k(L,Z,z)),k(L,N,z);for(let Q=H==1?a:l;Q>=a&&Q<=l;Q+=H){let ie=h[Q];if(ie==null)continue;let fe=y(u[Q]),he=A(ie);e==1?k(L,fe,z):k(L,F,he),k(L,fe,he),z=he,F=fe}let V=F;r&&e==1&&(V=R+w,k(L,V,z));let[le,q]=op(s,o);if(c.fill!=null||le!=0){let Q=D.fill=new Path2D(L),ie=c.fillTo(s,o,c.min,c.max,le),fe=A(ie);k(Q,V,fe),k(Q,Z,fe)}if(!c.spanGaps){let Q=[];Q.push(...ap(u,h,a,l,H,y,i));let ie=c.width*At/2,fe=t||e==1?ie:-ie,he=t||e==-1?-ie:ie;Q.forEach(ee=>{ee[0]+=fe,ee[1]+=he}),D.gaps=Q=c.gaps(s,o,a,l,Q),D.clip=Zc(Q,f.ori,m,g,v,T)}return q!=0&&(D.band=q==2?[Ur(s,o,a,l,L,-1),Ur(s,o,a,l,L,1)]:Ur(s,o,a,l,L,q)),D})}function I_(n,e,t,i,r,s,o=kt){if(n.length>1){let a=null;for(let l=0,c=1/0;l<n.length;l++)if(e[l]!==void 0){if(a!=null){let u=Tn(n[l]-n[a]);u<c&&(c=u,o=Tn(t(n[l],i,r,s)-t(n[a],i,r,s)))}a=l}}return o}function aA(n){n=n||Ka;let e=Et(n.size,[.6,kt,1]),t=n.align||0,i=n.gap||0,r=n.radius;r=r==null?[0,0]:typeof r=="number"?[r,0]:r;let s=xt(r),o=1-e[0],a=Et(e[1],kt),l=Et(e[2],1),c=Et(n.disp,Ka),u=Et(n.each,d=>{}),{fill:h,stroke:f}=c;return(d,p,x,m)=>Us(d,p,(g,v,T,M,R,w,y,A,k,D,L)=>{let H=g.pxRound,z=t,N=i*At,F=a*At,Z=l*At,V,le;M.ori==0?[V,le]=s(d,p):[le,V]=s(d,p);let q=M.dir*(M.ori==0?1:-1),Q=M.ori==0?qc:lp,ie=M.ori==0?u:(Ce,Ze,lt,we,Bt,He,Ye)=>{u(Ce,Ze,lt,Bt,we,Ye,He)},fe=Et(d.bands,tp).find(Ce=>Ce.series[0]==p),he=fe!=null?fe.dir:0,ee=g.fillTo(d,p,g.min,g.max,he),ge=H(y(ee,R,L,k)),ye,xe,_e,ze=D,$e=H(g.width*At),Fe=!1,st=null,ct=null,ot=null,qt=null;h!=null&&($e==0||f!=null)&&(Fe=!0,st=h.values(d,p,x,m),ct=new Map,new Set(st).forEach(Ce=>{Ce!=null&&ct.set(Ce,new Path2D)}),$e>0&&(ot=f.values(d,p,x,m),qt=new Map,new Set(ot).forEach(Ce=>{Ce!=null&&qt.set(Ce,new Path2D)})));let{x0:Gt,size:hn}=c;if(Gt!=null&&hn!=null){z=1,v=Gt.values(d,p,x,m),Gt.unit==2&&(v=v.map(lt=>d.posToVal(A+lt*D,M.key,!0)));let Ce=hn.values(d,p,x,m);hn.unit==2?xe=Ce[0]*D:xe=w(Ce[0],M,D,A)-w(0,M,D,A),ze=I_(v,T,w,M,D,A,ze),_e=ze-xe+N}else ze=I_(v,T,w,M,D,A,ze),_e=ze*o+N,xe=ze-_e;_e<1&&(_e=0),$e>=xe/2&&($e=0),_e<5&&(H=B_);let Ot=_e>0,Pn=ze-_e-(Ot?$e:0);xe=H(Hd(Pn,Z,F)),ye=(z==0?xe/2:z==q?0:xe)-z*q*((z==0?N/2:0)+(Ot?$e/2:0));let St={stroke:null,fill:null,clip:null,band:null,gaps:null,flags:0},En=Fe?null:new Path2D,tn=null;if(fe!=null)tn=d.data[fe.series[1]];else{let{y0:Ce,y1:Ze}=c;Ce!=null&&Ze!=null&&(T=Ze.values(d,p,x,m),tn=Ce.values(d,p,x,m))}let fn=V*xe,O=le*xe;for(let Ce=q==1?x:m;Ce>=x&&Ce<=m;Ce+=q){let Ze=T[Ce];if(Ze==null)continue;if(tn!=null){let X=tn[Ce]??0;if(Ze-X==0)continue;ge=y(X,R,L,k)}let lt=M.distr!=2||c!=null?v[Ce]:Ce,we=w(lt,M,D,A),Bt=y(Et(Ze,ee),R,L,k),He=H(we-ye),Ye=H(ri(Bt,ge)),I=H(Ki(Bt,ge)),b=Ye-I;if(Ze!=null){let X=Ze<0?O:fn,ue=Ze<0?fn:O;Fe?($e>0&&ot[Ce]!=null&&Q(qt.get(ot[Ce]),He,I+vi($e/2),xe,ri(0,b-$e),X,ue),st[Ce]!=null&&Q(ct.get(st[Ce]),He,I+vi($e/2),xe,ri(0,b-$e),X,ue)):Q(En,He,I+vi($e/2),xe,ri(0,b-$e),X,ue),ie(d,p,Ce,He-$e/2,I,xe+$e,b)}}return $e>0?St.stroke=Fe?qt:En:Fe||(St._fill=g.width==0?g._fill:g._stroke??g._fill,St.width=0),St.fill=Fe?ct:En,St})}function lA(n,e){let t=Et(e?.alignGaps,0);return(i,r,s,o)=>Us(i,r,(a,l,c,u,h,f,d,p,x,m,g)=>{[s,o]=Hc(c,s,o);let v=a.pxRound,T=V=>v(f(V,u,m,p)),M=V=>v(d(V,h,g,x)),R,w,y;u.ori==0?(R=Kc,y=Io,w=hx):(R=$c,y=Co,w=fx);let A=u.dir*(u.ori==0?1:-1),k=T(l[A==1?s:o]),D=k,L=[],H=[];for(let V=A==1?s:o;V>=s&&V<=o;V+=A)if(c[V]!=null){let q=l[V],Q=T(q);L.push(D=Q),H.push(M(c[V]))}let z={stroke:n(L,H,R,y,w,v),fill:null,clip:null,band:null,gaps:null,flags:To},N=z.stroke,[F,Z]=op(i,r);if(a.fill!=null||F!=0){let V=z.fill=new Path2D(N),le=a.fillTo(i,r,a.min,a.max,F),q=M(le);y(V,D,q),y(V,k,q)}if(!a.spanGaps){let V=[];V.push(...ap(l,c,s,o,A,T,t)),z.gaps=V=a.gaps(i,r,s,o,V),z.clip=Zc(V,u.ori,p,x,m,g)}return Z!=0&&(z.band=Z==2?[Ur(i,r,s,o,N,-1),Ur(i,r,s,o,N,1)]:Ur(i,r,s,o,N,Z)),z})}function cA(n){return lA(uA,n)}function uA(n,e,t,i,r,s){let o=n.length;if(o<2)return null;let a=new Path2D;if(t(a,n[0],e[0]),o==2)i(a,n[1],e[1]);else{let l=Array(o),c=Array(o-1),u=Array(o-1),h=Array(o-1);for(let f=0;f<o-1;f++)u[f]=e[f+1]-e[f],h[f]=n[f+1]-n[f],c[f]=u[f]/h[f];l[0]=c[0];for(let f=1;f<o-1;f++)c[f]===0||c[f-1]===0||c[f-1]>0!=c[f]>0?l[f]=0:(l[f]=3*(h[f-1]+h[f])/((2*h[f]+h[f-1])/c[f-1]+(h[f]+2*h[f-1])/c[f]),isFinite(l[f])||(l[f]=0));l[o-1]=c[o-2];for(let f=0;f<o-1;f++)r(a,n[f]+h[f]/3,e[f]+l[f]*h[f]/3,n[f+1]-h[f]/3,e[f+1]-l[f+1]*h[f]/3,n[f+1],e[f+1])}return a}var Zd=new Set;function C_(){for(let n of Zd)n.syncRect(!0)}Ro&&(Ls(WE,Mo,C_),Ls(XE,Mo,C_,!0),Ls(Vc,Mo,()=>{Rn.pxRatio=At}));var hA=mx(),fA=dx();function N_(n,e,t,i){return(i?[n[0],n[1]].concat(n.slice(2)):[n[0]].concat(n.slice(1))).map((s,o)=>Kd(s,o,e,t))}function dA(n,e){return n.map((t,i)=>i==0?{}:vn({},e,t))}function Kd(n,e,t,i){return vn({},e==0?t:i,n)}function gx(n,e,t){return e==null?wo:[e,t]}var pA=gx;function mA(n,e,t){return e==null?wo:Gc(e,t,Qd,!0)}function yx(n,e,t,i){return e==null?wo:Wc(e,t,n.scales[i].log,!1)}var gA=yx;function _x(n,e,t,i){return e==null?wo:jd(e,t,n.scales[i].log,!1)}var yA=_x;function _A(n,e,t,i,r){let s=ri(c_(n),c_(e)),o=e-n,a=Zi(r/i*o,t);do{let l=t[a],c=i*l/o;if(c>=r&&s+(l<5?is.get(l):0)<=17)return[l,c]}while(++a<t.length);return[0,0]}function P_(n){let e,t;return n=n.replace(/(\d+)px/,(i,r)=>(e=An((t=+r)*At))+"px"),[n,e,t]}function xA(n){n.show&&[n.font,n.labelFont].forEach(e=>{let t=Vt(e[2]*At,1);e[0]=e[0].replace(/[0-9.]+px/,t+"px"),e[1]=t})}function Rn(n,e,t){let i={mode:Et(n.mode,1)},r=i.mode;function s(_,S,C,P){let G=S.valToPct(_);return P+C*(S.dir==-1?1-G:G)}function o(_,S,C,P){let G=S.valToPct(_);return P+C*(S.dir==-1?G:1-G)}function a(_,S,C,P){return S.ori==0?s(_,S,C,P):o(_,S,C,P)}i.valToPosH=s,i.valToPosV=o;let l=!1;i.status=0;let c=i.root=Ni(AE);if(n.id!=null&&(c.id=n.id),xi(c,n.class),n.title){let _=Ni(IE,c);_.textContent=n.title}let u=Yi("canvas"),h=i.ctx=u.getContext("2d"),f=Ni(CE,c);Ls("click",f,_=>{_.target===p&&(Xt!=ro||Jt!=so)&&Vn.click(i,_)},!0);let d=i.under=Ni(NE,f);f.appendChild(u);let p=i.over=Ni(PE,f);n=Ao(n);let x=+Et(n.pxAlign,1),m=R_(x);(n.plugins||[]).forEach(_=>{_.opts&&(n=_.opts(i,n)||n)});let g=n.ms||.001,v=i.series=r==1?N_(n.series||[],b_,A_,!1):dA(n.series||[null],w_),T=i.axes=N_(n.axes||[],v_,M_,!0),M=i.scales={},R=i.bands=n.bands||[];R.forEach(_=>{_.fill=xt(_.fill||null),_.dir=Et(_.dir,-1)});let w=r==2?v[1].facets[0].scale:v[0].scale,y={axes:Tr,series:mt},A=(n.drawOrder||["axes","series"]).map(_=>y[_]);function k(_){let S=_.distr==3?C=>Dr(C>0?C:_.clamp(i,C,_.min,_.max,_.key)):_.distr==4?C=>Ud(C,_.asinh):_.distr==100?C=>_.fwd(C):C=>C;return C=>{let P=S(C),{_min:G,_max:J}=_,ae=J-G;return(P-G)/ae}}function D(_){let S=M[_];if(S==null){let C=(n.scales||Ka)[_]||Ka;if(C.from!=null){D(C.from);let P=vn({},M[C.from],C,{key:_});P.valToPct=k(P),M[_]=P}else{S=M[_]=vn({},_==w?ox:tA,C),S.key=_;let P=S.time,G=S.range,J=ns(G);if((_!=w||r==2&&!P)&&(J&&(G[0]==null||G[1]==null)&&(G={min:G[0]==null?o_:{mode:1,hard:G[0],soft:G[0]},max:G[1]==null?o_:{mode:1,hard:G[1],soft:G[1]}},J=!1),!J&&Yc(G))){let ae=G;G=(de,Me,De)=>Me==null?wo:Gc(Me,De,ae)}S.range=xt(G||(P?pA:_==w?S.distr==3?gA:S.distr==4?yA:gx:S.distr==3?yx:S.distr==4?_x:mA)),S.auto=xt(J?!1:S.auto),S.clamp=xt(S.clamp||eA),S._min=S._max=null,S.valToPct=k(S)}}}D("x"),D("y"),r==1&&v.forEach(_=>{D(_.scale)}),T.forEach(_=>{D(_.scale)});for(let _ in n.scales)D(_);let L=M[w],H=L.distr,z,N;L.ori==0?(xi(c,TE),z=s,N=o):(xi(c,RE),z=o,N=s);let F={};for(let _ in M){let S=M[_];(S.min!=null||S.max!=null)&&(F[_]={min:S.min,max:S.max},S.min=S.max=null)}let Z=n.tzDate||(_=>new Date(An(_/g))),V=n.fmtDate||np,le=g==1?Tw(Z):Cw(Z),q=y_(Z,g_(g==1?Aw:Iw,V)),Q=x_(Z,__(Pw,V)),ie=[],fe=i.legend=vn({},Uw,n.legend),he=i.cursor=vn({},Gw,{drag:{y:r==2}},n.cursor),ee=fe.show,ge=he.show,ye=fe.markers;fe.idxs=ie,ye.width=xt(ye.width),ye.dash=xt(ye.dash),ye.stroke=xt(ye.stroke),ye.fill=xt(ye.fill);let xe,_e,ze,$e=[],Fe=[],st,ct=!1,ot={};if(fe.live){let _=v[1]?v[1].values:null;ct=_!=null,st=ct?_(i,1,0):{_:0};for(let S in st)ot[S]=qd}if(ee)if(xe=Yi("table",BE,c),ze=Yi("tbody",null,xe),fe.mount(i,xe),ct){_e=Yi("thead",null,xe,ze);let _=Yi("tr",null,_e);Yi("th",null,_);for(var qt in st)Yi("th",Zy,_).textContent=qt}else xi(xe,VE),fe.live&&xi(xe,kE);let Gt={show:!0},hn={show:!1};function Ot(_,S){if(S==0&&(ct||!fe.live||r==2))return wo;let C=[],P=Yi("tr",GE,ze,ze.childNodes[S]);xi(P,_.class),_.show||xi(P,Ps);let G=Yi("th",null,P);if(ye.show){let de=Ni(zE,G);if(S>0){let Me=ye.width(i,S);Me&&(de.style.border=Me+"px "+ye.dash(i,S)+" "+ye.stroke(i,S)),de.style.background=ye.fill(i,S)}}let J=Ni(Zy,G);_.label instanceof HTMLElement?J.appendChild(_.label):J.textContent=_.label,S>0&&(ye.show||(J.style.color=_.width>0?ye.stroke(i,S):ye.fill(i,S)),St("click",G,de=>{if(he._lock)return;je(de);let Me=v.indexOf(_);if((de.ctrlKey||de.metaKey)!=fe.isolate){let De=v.some((Ue,Be)=>Be>0&&Be!=Me&&Ue.show);v.forEach((Ue,Be)=>{Be>0&&or(Be,De?Be==Me?Gt:hn:Gt,!0,gn.setSeries)})}else or(Me,{show:!_.show},!0,gn.setSeries)},!1),Qe&&St(Jy,G,de=>{he._lock||(je(de),or(v.indexOf(_),ao,!0,gn.setSeries))},!1));for(var ae in st){let de=Yi("td",HE,P);de.textContent="--",C.push(de)}return[P,C]}let Pn=new Map;function St(_,S,C,P=!0){let G=Pn.get(S)||{},J=he.bind[_](i,S,C,P);J&&(Ls(_,S,G[_]=J),Pn.set(S,G))}function En(_,S,C){let P=Pn.get(S)||{};for(let G in P)(_==null||G==_)&&(zd(G,S,P[G]),delete P[G]);_==null&&Pn.delete(S)}let tn=0,fn=0,O=0,Ce=0,Ze=0,lt=0,we=Ze,Bt=lt,He=O,Ye=Ce,I=0,b=0,X=0,ue=0;i.bbox={};let oe=!1,be=!1,Se=!1,te=!1,re=!1,pe=!1;function U(_,S,C){(C||_!=i.width||S!=i.height)&&se(_,S),ht(!1),Se=!0,be=!0,Hn()}function se(_,S){i.width=tn=O=_,i.height=fn=Ce=S,Ze=lt=0,Ee(),We();let C=i.bbox;I=C.left=Cs(Ze*At,.5),b=C.top=Cs(lt*At,.5),X=C.width=Cs(O*At,.5),ue=C.height=Cs(Ce*At,.5)}let ne=3;function Ae(){let _=!1,S=0;for(;!_;){S++;let C=to(S),P=sr(S);_=S==ne||C&&P,_||(se(i.width,i.height),be=!0)}}function ve({width:_,height:S}){U(_,S)}i.setSize=ve;function Ee(){let _=!1,S=!1,C=!1,P=!1;T.forEach((G,J)=>{if(G.show&&G._show){let{side:ae,_size:de}=G,Me=ae%2,De=G.label!=null?G.labelSize:0,Ue=de+De;Ue>0&&(Me?(O-=Ue,ae==3?(Ze+=Ue,P=!0):C=!0):(Ce-=Ue,ae==0?(lt+=Ue,_=!0):S=!0))}}),ir[0]=_,ir[1]=C,ir[2]=S,ir[3]=P,O-=Bi[1]+Bi[3],Ze+=Bi[3],Ce-=Bi[2]+Bi[0],lt+=Bi[0]}function We(){let _=Ze+O,S=lt+Ce,C=Ze,P=lt;function G(J,ae){switch(J){case 1:return _+=ae,_-ae;case 2:return S+=ae,S-ae;case 3:return C-=ae,C+ae;case 0:return P-=ae,P+ae}}T.forEach((J,ae)=>{if(J.show&&J._show){let de=J.side;J._pos=G(de,J._size),J.label!=null&&(J._lpos=G(de,J.labelSize))}})}if(he.dataIdx==null){let _=he.hover,S=_.skip=new Set(_.skip??[]);S.add(void 0);let C=_.prox=xt(_.prox),P=_.bias??=0;he.dataIdx=(G,J,ae,de)=>{if(J==0)return ae;let Me=ae,De=C(G,J,ae,de)??kt,Ue=De>=0&&De<kt,Be=L.ori==0?O:Ce,at=he.left,wt=e[0],Mt=e[J];if(S.has(Mt[ae])){Me=null;let yt=null,qe=null,Xe;if(P==0||P==-1)for(Xe=ae;yt==null&&Xe-- >0;)S.has(Mt[Xe])||(yt=Xe);if(P==0||P==1)for(Xe=ae;qe==null&&Xe++<Mt.length;)S.has(Mt[Xe])||(qe=Xe);if(yt!=null||qe!=null)if(Ue){let Zt=yt==null?-1/0:z(wt[yt],L,Be,0),sn=qe==null?1/0:z(wt[qe],L,Be,0),On=at-Zt,Ft=sn-at;On<=Ft?On<=De&&(Me=yt):Ft<=De&&(Me=qe)}else Me=qe==null?yt:yt==null?qe:ae-yt<=qe-ae?yt:qe}else Ue&&Tn(at-z(wt[ae],L,Be,0))>De&&(Me=null);return Me}}let je=_=>{he.event=_};he.idxs=ie,he._lock=!1;let ce=he.points;ce.show=xt(ce.show),ce.size=xt(ce.size),ce.stroke=xt(ce.stroke),ce.width=xt(ce.width),ce.fill=xt(ce.fill);let ke=i.focus=vn({},n.focus||{alpha:.3},he.focus),Qe=ke.prox>=0,Ie=Qe&&ce.one,ut=[],Wt=[],jn=[];function pa(_,S){let C=ce.show(i,S);if(C instanceof HTMLElement)return xi(C,FE),xi(C,_.class),fr(C,-10,-10,O,Ce),p.insertBefore(C,ut[S]),C}function js(_,S){if(r==1||S>0){let C=r==1&&M[_.scale].time,P=_.value;_.value=C?f_(P)?x_(Z,__(P,V)):P||Q:P||Jw,_.label=_.label||(C?Hw:zw)}if(Ie||S>0){_.width=_.width==null?1:_.width,_.paths=_.paths||hA||tw,_.fillTo=xt(_.fillTo||nA),_.pxAlign=+Et(_.pxAlign,x),_.pxRound=R_(_.pxAlign),_.stroke=xt(_.stroke||null),_.fill=xt(_.fill||null),_._stroke=_._fill=_._paths=_._focus=null;let C=jw(ri(1,_.width),1),P=_.points=vn({},{size:C,width:ri(1,C*.2),stroke:_.stroke,space:C*2,paths:fA,_stroke:null,_fill:null},_.points);P.show=xt(P.show),P.filter=xt(P.filter),P.fill=xt(P.fill),P.stroke=xt(P.stroke),P.paths=xt(P.paths),P.pxAlign=_.pxAlign}if(ee){let C=Ot(_,S);$e.splice(S,0,C[0]),Fe.splice(S,0,C[1]),fe.values.push(null)}if(ge){ie.splice(S,0,null);let C=null;Ie?S==0&&(C=pa(_,S)):S>0&&(C=pa(_,S)),ut.splice(S,0,C),Wt.splice(S,0,0),jn.splice(S,0,0)}Un("addSeries",S)}function yf(_,S){S=S??v.length,_=r==1?Kd(_,S,b_,A_):Kd(_,S,{},w_),v.splice(S,0,_),js(v[S],S)}i.addSeries=yf;function Yl(_){if(v.splice(_,1),ee){fe.values.splice(_,1),Fe.splice(_,1);let S=$e.splice(_,1)[0];En(null,S.firstChild),S.remove()}ge&&(ie.splice(_,1),ut.splice(_,1)[0].remove(),Wt.splice(_,1),jn.splice(_,1)),Un("delSeries",_)}i.delSeries=Yl;let ir=[!1,!1,!1,!1];function Er(_,S){if(_._show=_.show,_.show){let C=_.side%2,P=M[_.scale];P==null&&(_.scale=C?v[1].scale:w,P=M[_.scale]);let G=P.time;_.size=xt(_.size),_.space=xt(_.space),_.rotate=xt(_.rotate),ns(_.incrs)&&_.incrs.forEach(ae=>{!is.has(ae)&&is.set(ae,G_(ae))}),_.incrs=xt(_.incrs||(P.distr==2?Mw:G?g==1?ww:Rw:Ns)),_.splits=xt(_.splits||(G&&P.distr==1?le:P.distr==3?Wd:P.distr==4?Yw:Xw)),_.stroke=xt(_.stroke),_.grid.stroke=xt(_.grid.stroke),_.ticks.stroke=xt(_.ticks.stroke),_.border.stroke=xt(_.border.stroke);let J=_.values;_.values=ns(J)&&!ns(J[0])?xt(J):G?ns(J)?y_(Z,g_(J,V)):f_(J)?Nw(Z,J):J||q:J||Ww,_.filter=xt(_.filter||(P.distr>=3&&P.log==10?$w:P.distr==3&&P.log==2?qw:k_)),_.font=P_(_.font),_.labelFont=P_(_.labelFont),_._size=_.size(i,null,S,0),_._space=_._rotate=_._incrs=_._found=_._splits=_._values=null,_._size>0&&(ir[S]=!0,_._el=Ni(LE,f))}}function wr(_,S,C,P){let[G,J,ae,de]=C,Me=S%2,De=0;return Me==0&&(de||J)&&(De=S==0&&!G||S==2&&!ae?An(v_.size/3):0),Me==1&&(G||ae)&&(De=S==1&&!J||S==3&&!de?An(M_.size/2):0),De}let ma=i.padding=(n.padding||[wr,wr,wr,wr]).map(_=>xt(Et(_,wr))),Bi=i._padding=ma.map((_,S)=>_(i,S,ir,0)),nn,ln=null,cn=null,rr=r==1?v[0].idxs:null,mi=null,Kr=!1;function ga(_,S){if(e=_??[],i.data=i._data=e,r==2){nn=0;for(let C=1;C<v.length;C++)nn+=e[C][0].length}else{e.length==0&&(i.data=i._data=e=[[]]),mi=e[0],nn=mi.length;let C=e;if(H==2){C=e.slice();let P=C[0]=Array(nn);for(let G=0;G<nn;G++)P[G]=G}i._data=e=C}if(ht(!0),Un("setData"),H==2&&(Se=!0),S!==!1){let C=L;C.auto(i,Kr)?ya():Jr(w,C.min,C.max),te=te||he.left>=0,pe=!0,Hn()}}i.setData=ga;function ya(){Kr=!0;let _,S;r==1&&(nn>0?(ln=rr[0]=0,cn=rr[1]=nn-1,_=e[0][ln],S=e[0][cn],H==2?(_=ln,S=cn):_==S&&(H==3?[_,S]=Wc(_,_,L.log,!1):H==4?[_,S]=jd(_,_,L.log,!1):L.time?S=_+An(86400/g):[_,S]=Gc(_,S,Qd,!0))):(ln=rr[0]=_=null,cn=rr[1]=S=null)),Jr(w,_,S)}let Qs,$r,eo,E,B,j,K,$,Te,Ne;function Re(_,S,C,P,G,J){_??=$y,C??=tp,P??="butt",G??=$y,J??="round",_!=Qs&&(h.strokeStyle=Qs=_),G!=$r&&(h.fillStyle=$r=G),S!=eo&&(h.lineWidth=eo=S),J!=B&&(h.lineJoin=B=J),P!=j&&(h.lineCap=j=P),C!=E&&h.setLineDash(E=C)}function Pe(_,S,C,P){S!=$r&&(h.fillStyle=$r=S),_!=K&&(h.font=K=_),C!=$&&(h.textAlign=$=C),P!=Te&&(h.textBaseline=Te=P)}function Ge(_,S,C,P,G=0){if(P.length>0&&_.auto(i,Kr)&&(S==null||S.min==null)){let J=Et(ln,0),ae=Et(cn,P.length-1),de=C.min==null?$E(P,J,ae,G,_.distr==3):[C.min,C.max];_.min=Ki(_.min,C.min=de[0]),_.max=ri(_.max,C.max=de[1])}}let tt={min:null,max:null};function pt(){for(let P in M){let G=M[P];F[P]==null&&(G.min==null||F[w]!=null&&G.auto(i,Kr))&&(F[P]=tt)}for(let P in M){let G=M[P];F[P]==null&&G.from!=null&&F[G.from]!=null&&(F[P]=tt)}F[w]!=null&&ht(!0);let _={};for(let P in F){let G=F[P];if(G!=null){let J=_[P]=Ao(M[P],rw);if(G.min!=null)vn(J,G);else if(P!=w||r==2)if(nn==0&&J.from==null){let ae=J.range(i,null,null,P);J.min=ae[0],J.max=ae[1]}else J.min=kt,J.max=-kt}}if(nn>0){v.forEach((P,G)=>{if(r==1){let J=P.scale,ae=F[J];if(ae==null)return;let de=_[J];if(G==0){let Me=de.range(i,de.min,de.max,J);de.min=Me[0],de.max=Me[1],ln=Zi(de.min,e[0]),cn=Zi(de.max,e[0]),cn-ln>1&&(e[0][ln]<de.min&&ln++,e[0][cn]>de.max&&cn--),P.min=mi[ln],P.max=mi[cn]}else P.show&&P.auto&&Ge(de,ae,P,e[G],P.sorted);P.idxs[0]=ln,P.idxs[1]=cn}else if(G>0&&P.show&&P.auto){let[J,ae]=P.facets,de=J.scale,Me=ae.scale,[De,Ue]=e[G],Be=_[de],at=_[Me];Be!=null&&Ge(Be,F[de],J,De,J.sorted),at!=null&&Ge(at,F[Me],ae,Ue,ae.sorted),P.min=ae.min,P.max=ae.max}});for(let P in _){let G=_[P],J=F[P];if(G.from==null&&(J==null||J.min==null)){let ae=G.range(i,G.min==kt?null:G.min,G.max==-kt?null:G.max,P);G.min=ae[0],G.max=ae[1]}}}for(let P in _){let G=_[P];if(G.from!=null){let J=_[G.from];if(J.min==null)G.min=G.max=null;else{let ae=G.range(i,J.min,J.max,P);G.min=ae[0],G.max=ae[1]}}}let S={},C=!1;for(let P in _){let G=_[P],J=M[P];if(J.min!=G.min||J.max!=G.max){J.min=G.min,J.max=G.max;let ae=J.distr;J._min=ae==3?Dr(J.min):ae==4?Ud(J.min,J.asinh):ae==100?J.fwd(J.min):J.min,J._max=ae==3?Dr(J.max):ae==4?Ud(J.max,J.asinh):ae==100?J.fwd(J.max):J.max,S[P]=C=!0}}if(C){v.forEach((P,G)=>{r==2?G>0&&S.y&&(P._paths=null):S[P.scale]&&(P._paths=null)});for(let P in S)Se=!0,Un("setScale",P);ge&&he.left>=0&&(te=pe=!0)}for(let P in F)F[P]=null}function Ve(_){let S=Hd(ln-1,0,nn-1),C=Hd(cn+1,0,nn-1);for(;_[S]==null&&S>0;)S--;for(;_[C]==null&&C<nn-1;)C++;return[S,C]}function mt(){if(nn>0){let _=v.some(S=>S._focus)&&Ne!=ke.alpha;_&&(h.globalAlpha=Ne=ke.alpha),v.forEach((S,C)=>{if(C>0&&S.show&&(Qt(C,!1),Qt(C,!0),S._paths==null)){let P=Ne;Ne!=S.alpha&&(h.globalAlpha=Ne=S.alpha);let G=r==2?[0,e[C][0].length-1]:Ve(e[C]);S._paths=S.paths(i,C,G[0],G[1]),Ne!=P&&(h.globalAlpha=Ne=P)}}),v.forEach((S,C)=>{if(C>0&&S.show){let P=Ne;Ne!=S.alpha&&(h.globalAlpha=Ne=S.alpha),S._paths!=null&&Pt(C,!1);{let G=S._paths!=null?S._paths.gaps:null,J=S.points.show(i,C,ln,cn,G),ae=S.points.filter(i,C,J,G);(J||ae)&&(S.points._paths=S.points.paths(i,C,ln,cn,ae),Pt(C,!0))}Ne!=P&&(h.globalAlpha=Ne=P),Un("drawSeries",C)}}),_&&(h.globalAlpha=Ne=1)}}function Qt(_,S){let C=S?v[_].points:v[_];C._stroke=C.stroke(i,_),C._fill=C.fill(i,_)}function Pt(_,S){let C=S?v[_].points:v[_],{stroke:P,fill:G,clip:J,flags:ae,_stroke:de=C._stroke,_fill:Me=C._fill,_width:De=C.width}=C._paths;De=Vt(De*At,3);let Ue=null,Be=De%2/2;S&&Me==null&&(Me=De>0?"#fff":de);let at=C.pxAlign==1&&Be>0;if(at&&h.translate(Be,Be),!S){let wt=I-De/2,Mt=b-De/2,yt=X+De,qe=ue+De;Ue=new Path2D,Ue.rect(wt,Mt,yt,qe)}S?Oe(de,De,C.dash,C.cap,Me,P,G,ae,J):Lt(_,de,De,C.dash,C.cap,Me,P,G,ae,Ue,J),at&&h.translate(-Be,-Be)}function Lt(_,S,C,P,G,J,ae,de,Me,De,Ue){let Be=!1;Me!=0&&R.forEach((at,wt)=>{if(at.series[0]==_){let Mt=v[at.series[1]],yt=e[at.series[1]],qe=(Mt._paths||Ka).band;ns(qe)&&(qe=at.dir==1?qe[0]:qe[1]);let Xe,Zt=null;Mt.show&&qe&&JE(yt,ln,cn)?(Zt=at.fill(i,wt)||J,Xe=Mt._paths.clip):qe=null,Oe(S,C,P,G,Zt,ae,de,Me,De,Ue,Xe,qe),Be=!0}}),Be||Oe(S,C,P,G,J,ae,de,Me,De,Ue)}let wn=To|Yd;function Oe(_,S,C,P,G,J,ae,de,Me,De,Ue,Be){Re(_,S,C,P,G),(Me||De||Be)&&(h.save(),Me&&h.clip(Me),De&&h.clip(De)),Be?(de&wn)==wn?(h.clip(Be),Ue&&h.clip(Ue),_t(G,ae),dn(_,J,S)):de&Yd?(_t(G,ae),h.clip(Be),dn(_,J,S)):de&To&&(h.save(),h.clip(Be),Ue&&h.clip(Ue),_t(G,ae),h.restore(),dn(_,J,S)):(_t(G,ae),dn(_,J,S)),(Me||De||Be)&&h.restore()}function dn(_,S,C){C>0&&(S instanceof Map?S.forEach((P,G)=>{h.strokeStyle=Qs=G,h.stroke(P)}):S!=null&&_&&h.stroke(S))}function _t(_,S){S instanceof Map?S.forEach((C,P)=>{h.fillStyle=$r=P,h.fill(C)}):S!=null&&_&&h.fill(S)}function Ar(_,S,C,P){let G=T[_],J;if(P<=0)J=[0,0];else{let ae=G._space=G.space(i,_,S,C,P),de=G._incrs=G.incrs(i,_,S,C,P,ae);J=_A(S,C,de,P,ae)}return G._found=J}function pn(_,S,C,P,G,J,ae,de,Me,De){let Ue=ae%2/2;x==1&&h.translate(Ue,Ue),Re(de,ae,Me,De,de),h.beginPath();let Be,at,wt,Mt,yt=G+(P==0||P==3?-J:J);C==0?(at=G,Mt=yt):(Be=G,wt=yt);for(let qe=0;qe<_.length;qe++)S[qe]!=null&&(C==0?Be=wt=_[qe]:at=Mt=_[qe],h.moveTo(Be,at),h.lineTo(wt,Mt));h.stroke(),x==1&&h.translate(-Ue,-Ue)}function to(_){let S=!0;return T.forEach((C,P)=>{if(!C.show)return;let G=M[C.scale];if(G.min==null){C._show&&(S=!1,C._show=!1,ht(!1));return}else C._show||(S=!1,C._show=!0,ht(!1));let J=C.side,ae=J%2,{min:de,max:Me}=G,[De,Ue]=Ar(P,de,Me,ae==0?O:Ce);if(Ue==0)return;let Be=G.distr==2,at=C._splits=C.splits(i,P,de,Me,De,Ue,Be),wt=G.distr==2?at.map(Xe=>mi[Xe]):at,Mt=G.distr==2?mi[at[1]]-mi[at[0]]:De,yt=C._values=C.values(i,C.filter(i,wt,P,Ue,Mt),P,Ue,Mt);C._rotate=J==2?C.rotate(i,yt,P,Ue):0;let qe=C._size;C._size=Pi(C.size(i,yt,P,_)),qe!=null&&C._size!=qe&&(S=!1)}),S}function sr(_){let S=!0;return ma.forEach((C,P)=>{let G=C(i,P,ir,_);G!=Bi[P]&&(S=!1),Bi[P]=G}),S}function Tr(){for(let _=0;_<T.length;_++){let S=T[_];if(!S.show||!S._show)continue;let C=S.side,P=C%2,G,J,ae=S.stroke(i,_),de=C==0||C==3?-1:1,[Me,De]=S._found;if(S.label!=null){let ti=S.labelGap*de,_i=An((S._lpos+ti)*At);Pe(S.labelFont[0],ae,"center",C==2?"top":Ky),h.save(),P==1?(G=J=0,h.translate(_i,An(b+ue/2)),h.rotate((C==3?-kc:kc)/2)):(G=An(I+X/2),J=_i);let Es=F_(S.label)?S.label(i,_,Me,De):S.label;h.fillText(Es,G,J),h.restore()}if(De==0)continue;let Ue=M[S.scale],Be=P==0?X:ue,at=P==0?I:b,wt=S._splits,Mt=Ue.distr==2?wt.map(ti=>mi[ti]):wt,yt=Ue.distr==2?mi[wt[1]]-mi[wt[0]]:Me,qe=S.ticks,Xe=S.border,Zt=qe.show?qe.size:0,sn=An(Zt*At),On=An((S.alignTo==2?S._size-Zt-S.gap:S.gap)*At),Ft=S._rotate*-kc/180,on=m(S._pos*At),gi=(sn+On)*de,ei=on+gi;J=P==0?ei:0,G=P==1?ei:0;let Ii=S.font[0],ki=S.align==1?bo:S.align==2?Pd:Ft>0?bo:Ft<0?Pd:P==0?"center":C==3?Pd:bo,lr=Ft||P==1?"middle":C==2?"top":Ky;Pe(Ii,ae,ki,lr);let yi=S.font[1]*S.lineGap,Ci=wt.map(ti=>m(a(ti,Ue,Be,at))),Vi=S._values;for(let ti=0;ti<Vi.length;ti++){let _i=Vi[ti];if(_i!=null){P==0?G=Ci[ti]:J=Ci[ti],_i=""+_i;let Es=_i.indexOf(`
`)==-1?[_i]:_i.split(/\n/gm);for(let ni=0;ni<Es.length;ni++){let yg=Es[ni];Ft?(h.save(),h.translate(G,J+ni*yi),h.rotate(Ft),h.fillText(yg,0,0),h.restore()):h.fillText(yg,G,J+ni*yi)}}}qe.show&&pn(Ci,qe.filter(i,Mt,_,De,yt),P,C,on,sn,Vt(qe.width*At,3),qe.stroke(i,_),qe.dash,qe.cap);let cr=S.grid;cr.show&&pn(Ci,cr.filter(i,Mt,_,De,yt),P,P==0?2:1,P==0?b:I,P==0?ue:X,Vt(cr.width*At,3),cr.stroke(i,_),cr.dash,cr.cap),Xe.show&&pn([on],[1],P==0?1:0,P==0?1:2,P==1?b:I,P==1?ue:X,Vt(Xe.width*At,3),Xe.stroke(i,_),Xe.dash,Xe.cap)}Un("drawAxes")}function ht(_){v.forEach((S,C)=>{C>0&&(S._paths=null,_&&(r==1?(S.min=null,S.max=null):S.facets.forEach(P=>{P.min=null,P.max=null})))})}let rn=!1,Qn=!1,Dt=[];function mn(){Qn=!1;for(let _=0;_<Dt.length;_++)Un(...Dt[_]);Dt.length=0}function Hn(){rn||(hw(Qm),rn=!0)}function Zl(_,S=!1){rn=!0,Qn=S,_(i),Qm(),S&&Dt.length>0&&queueMicrotask(mn)}i.batch=Zl;function Qm(){if(oe&&(pt(),oe=!1),Se&&(Ae(),Se=!1),be){if(Kt(d,bo,Ze),Kt(d,"top",lt),Kt(d,Wa,O),Kt(d,Xa,Ce),Kt(p,bo,Ze),Kt(p,"top",lt),Kt(p,Wa,O),Kt(p,Xa,Ce),Kt(f,Wa,tn),Kt(f,Xa,fn),u.width=An(tn*At),u.height=An(fn*At),T.forEach(({_el:_,_show:S,_size:C,_pos:P,side:G})=>{if(_!=null)if(S){let J=G===3||G===0?C:0,ae=G%2==1;Kt(_,ae?"left":"top",P-J),Kt(_,ae?"width":"height",C),Kt(_,ae?"top":"left",ae?lt:Ze),Kt(_,ae?"height":"width",ae?Ce:O),Gd(_,Ps)}else xi(_,Ps)}),Qs=$r=eo=B=j=K=$=Te=E=null,Ne=1,va(!0),Ze!=we||lt!=Bt||O!=He||Ce!=Ye){ht(!1);let _=O/He,S=Ce/Ye;if(ge&&!te&&he.left>=0){he.left*=_,he.top*=S,no&&fr(no,An(he.left),0,O,Ce),io&&fr(io,0,An(he.top),O,Ce);for(let C=0;C<ut.length;C++){let P=ut[C];P!=null&&(Wt[C]*=_,jn[C]*=S,fr(P,Pi(Wt[C]),Pi(jn[C]),O,Ce))}}if(Yt.show&&!re&&Yt.left>=0&&Yt.width>0){Yt.left*=_,Yt.width*=_,Yt.top*=S,Yt.height*=S;for(let C in Mf)Kt(oo,C,Yt[C])}we=Ze,Bt=lt,He=O,Ye=Ce}Un("setSize"),be=!1}tn>0&&fn>0&&(h.clearRect(0,0,u.width,u.height),Un("drawClear"),A.forEach(_=>_()),Un("draw")),Yt.show&&re&&(Kl(Yt),re=!1),ge&&te&&(Ms(null,!0,!1),te=!1),fe.show&&fe.live&&pe&&(bf(),pe=!1),l||(l=!0,i.status=1,Un("ready")),Kr=!1,rn=!1}i.redraw=(_,S)=>{Se=S||!1,_!==!1?Jr(w,L.min,L.max):Hn()};function _f(_,S){let C=M[_];if(C.from==null){if(nn==0){let P=C.range(i,S.min,S.max,_);S.min=P[0],S.max=P[1]}if(S.min>S.max){let P=S.min;S.min=S.max,S.max=P}if(nn>1&&S.min!=null&&S.max!=null&&S.max-S.min<1e-16)return;_==w&&C.distr==2&&nn>0&&(S.min=Zi(S.min,e[0]),S.max=Zi(S.max,e[0]),S.min==S.max&&S.max++),F[_]=S,oe=!0,Hn()}}i.setScale=_f;let xf,vf,no,io,eg,tg,ro,so,ng,ig,Xt,Jt,qr=!1,Vn=he.drag,Ln=Vn.x,Dn=Vn.y;ge&&(he.x&&(xf=Ni(UE,p)),he.y&&(vf=Ni(OE,p)),L.ori==0?(no=xf,io=vf):(no=vf,io=xf),Xt=he.left,Jt=he.top);let Yt=i.select=vn({show:!0,over:!0,left:0,width:0,top:0,height:0},n.select),oo=Yt.show?Ni(DE,Yt.over?p:d):null;function Kl(_,S){if(Yt.show){for(let C in _)Yt[C]=_[C],C in Mf&&Kt(oo,C,_[C]);S!==!1&&Un("setSelect")}}i.setSelect=Kl;function hS(_){if(v[_].show)ee&&Gd($e[_],Ps);else if(ee&&xi($e[_],Ps),ge){let C=Ie?ut[0]:ut[_];C!=null&&fr(C,-10,-10,O,Ce)}}function Jr(_,S,C){_f(_,{min:S,max:C})}function or(_,S,C,P){S.focus!=null&&gS(_),S.show!=null&&v.forEach((G,J)=>{J>0&&(_==J||_==null)&&(G.show=S.show,hS(J),r==2?(Jr(G.facets[0].scale,null,null),Jr(G.facets[1].scale,null,null)):Jr(G.scale,null,null),Hn())}),C!==!1&&Un("setSeries",_,S),P&&ba("setSeries",i,_,S)}i.setSeries=or;function fS(_,S){vn(R[_],S)}function dS(_,S){_.fill=xt(_.fill||null),_.dir=Et(_.dir,-1),S=S??R.length,R.splice(S,0,_)}function pS(_){_==null?R.length=0:R.splice(_,1)}i.addBand=dS,i.setBand=fS,i.delBand=pS;function mS(_,S){v[_].alpha=S,ge&&ut[_]!=null&&(ut[_].style.opacity=S),ee&&$e[_]&&($e[_].style.opacity=S)}let Rr,jr,Ss,ao={focus:!0};function gS(_){if(_!=Ss){let S=_==null,C=ke.alpha!=1;v.forEach((P,G)=>{if(r==1||G>0){let J=S||G==0||G==_;P._focus=S?null:J,C&&mS(G,J?1:ke.alpha)}}),Ss=_,C&&Hn()}}ee&&Qe&&St(jy,xe,_=>{he._lock||(je(_),Ss!=null&&or(null,ao,!0,gn.setSeries))});function ar(_,S,C){let P=M[S];C&&(_=_/At-(P.ori==1?lt:Ze));let G=O;P.ori==1&&(G=Ce,_=G-_),P.dir==-1&&(_=G-_);let J=P._min,ae=P._max,de=_/G,Me=J+(ae-J)*de,De=P.distr;return De==3?Eo(10,Me):De==4?QE(Me,P.asinh):De==100?P.bwd(Me):Me}function yS(_,S){let C=ar(_,w,S);return Zi(C,e[0],ln,cn)}i.valToIdx=_=>Zi(_,e[0]),i.posToIdx=yS,i.posToVal=ar,i.valToPos=(_,S,C)=>M[S].ori==0?s(_,M[S],C?X:O,C?I:0):o(_,M[S],C?ue:Ce,C?b:0),i.setCursor=(_,S,C)=>{Xt=_.left,Jt=_.top,Ms(null,S,C)};function rg(_,S){Kt(oo,bo,Yt.left=_),Kt(oo,Wa,Yt.width=S)}function sg(_,S){Kt(oo,"top",Yt.top=_),Kt(oo,Xa,Yt.height=S)}let _a=L.ori==0?rg:sg,xa=L.ori==1?rg:sg;function _S(){if(ee&&fe.live)for(let _=r==2?1:0;_<v.length;_++){if(_==0&&ct)continue;let S=fe.values[_],C=0;for(let P in S)Fe[_][C++].firstChild.nodeValue=S[P]}}function bf(_,S){if(_!=null&&(_.idxs?_.idxs.forEach((C,P)=>{ie[P]=C}):iw(_.idx)||ie.fill(_.idx),fe.idx=ie[0]),ee&&fe.live){for(let C=0;C<v.length;C++)(C>0||r==1&&!ct)&&xS(C,ie[C]);_S()}pe=!1,S!==!1&&Un("setLegend")}i.setLegend=bf;function xS(_,S){let C=v[_],P=_==0&&H==2?mi:e[_],G;ct?G=C.values(i,_,S)??ot:(G=C.value(i,S==null?null:P[S],_,S),G=G==null?ot:{_:G}),fe.values[_]=G}function Ms(_,S,C){ng=Xt,ig=Jt,[Xt,Jt]=he.move(i,Xt,Jt),he.left=Xt,he.top=Jt,ge&&(no&&fr(no,An(Xt),0,O,Ce),io&&fr(io,0,An(Jt),O,Ce));let P,G=ln>cn;Rr=kt,jr=null;let J=L.ori==0?O:Ce,ae=L.ori==1?O:Ce;if(Xt<0||nn==0||G){P=he.idx=null;for(let de=0;de<v.length;de++){let Me=ut[de];Me!=null&&fr(Me,-10,-10,O,Ce)}Qe&&or(null,ao,!0,_==null&&gn.setSeries),fe.live&&(ie.fill(P),pe=!0)}else{let de,Me,De;r==1&&(de=L.ori==0?Xt:Jt,Me=ar(de,w),P=he.idx=Zi(Me,e[0],ln,cn),De=z(e[0][P],L,J,0));let Ue=-10,Be=-10,at=0,wt=0,Mt=!0,yt="",qe="";for(let Xe=r==2?1:0;Xe<v.length;Xe++){let Zt=v[Xe],sn=ie[Xe],On=sn==null?null:r==1?e[Xe][sn]:e[Xe][1][sn],Ft=he.dataIdx(i,Xe,P,Me),on=Ft==null?null:r==1?e[Xe][Ft]:e[Xe][1][Ft];if(pe=pe||on!=On||Ft!=sn,ie[Xe]=Ft,Xe>0&&Zt.show){let gi=Ft==null?-10:Ft==P?De:z(r==1?e[0][Ft]:e[Xe][0][Ft],L,J,0),ei=on==null?-10:N(on,r==1?M[Zt.scale]:M[Zt.facets[1].scale],ae,0);if(Qe&&on!=null){let Ii=L.ori==1?Xt:Jt,ki=Tn(ke.dist(i,Xe,Ft,ei,Ii));if(ki<Rr){let lr=ke.bias;if(lr!=0){let yi=ar(Ii,Zt.scale),Ci=on>=0?1:-1,Vi=yi>=0?1:-1;Vi==Ci&&(Vi==1?lr==1?on>=yi:on<=yi:lr==1?on<=yi:on>=yi)&&(Rr=ki,jr=Xe)}else Rr=ki,jr=Xe}}if(pe||Ie){let Ii,ki;L.ori==0?(Ii=gi,ki=ei):(Ii=ei,ki=gi);let lr,yi,Ci,Vi,cr,ti,_i=!0,Es=ce.bbox;if(Es!=null){_i=!1;let ni=Es(i,Xe);Ci=ni.left,Vi=ni.top,lr=ni.width,yi=ni.height}else Ci=Ii,Vi=ki,lr=yi=ce.size(i,Xe);if(ti=ce.fill(i,Xe),cr=ce.stroke(i,Xe),Ie)Xe==jr&&Rr<=ke.prox&&(Ue=Ci,Be=Vi,at=lr,wt=yi,Mt=_i,yt=ti,qe=cr);else{let ni=ut[Xe];ni!=null&&(Wt[Xe]=Ci,jn[Xe]=Vi,s_(ni,lr,yi,_i),i_(ni,ti,cr),fr(ni,Pi(Ci),Pi(Vi),O,Ce))}}}}if(Ie){let Xe=ke.prox,Zt=Ss==null?Rr<=Xe:Rr>Xe||jr!=Ss;if(pe||Zt){let sn=ut[0];sn!=null&&(Wt[0]=Ue,jn[0]=Be,s_(sn,at,wt,Mt),i_(sn,yt,qe),fr(sn,Pi(Ue),Pi(Be),O,Ce))}}}if(Yt.show&&qr)if(_!=null){let[de,Me]=gn.scales,[De,Ue]=gn.match,[Be,at]=_.cursor.sync.scales,wt=_.cursor.drag;if(Ln=wt._x,Dn=wt._y,Ln||Dn){let{left:Mt,top:yt,width:qe,height:Xe}=_.select,Zt=_.scales[Be].ori,sn=_.posToVal,On,Ft,on,gi,ei,Ii=de!=null&&De(de,Be),ki=Me!=null&&Ue(Me,at);Ii&&Ln?(Zt==0?(On=Mt,Ft=qe):(On=yt,Ft=Xe),on=M[de],gi=z(sn(On,Be),on,J,0),ei=z(sn(On+Ft,Be),on,J,0),_a(Ki(gi,ei),Tn(ei-gi))):_a(0,J),ki&&Dn?(Zt==1?(On=Mt,Ft=qe):(On=yt,Ft=Xe),on=M[Me],gi=N(sn(On,at),on,ae,0),ei=N(sn(On+Ft,at),on,ae,0),xa(Ki(gi,ei),Tn(ei-gi))):xa(0,ae)}else Ef()}else{let de=Tn(ng-eg),Me=Tn(ig-tg);if(L.ori==1){let at=de;de=Me,Me=at}Ln=Vn.x&&de>=Vn.dist,Dn=Vn.y&&Me>=Vn.dist;let De=Vn.uni;De!=null?Ln&&Dn&&(Ln=de>=De,Dn=Me>=De,!Ln&&!Dn&&(Me>de?Dn=!0:Ln=!0)):Vn.x&&Vn.y&&(Ln||Dn)&&(Ln=Dn=!0);let Ue,Be;Ln&&(L.ori==0?(Ue=ro,Be=Xt):(Ue=so,Be=Jt),_a(Ki(Ue,Be),Tn(Be-Ue)),Dn||xa(0,ae)),Dn&&(L.ori==1?(Ue=ro,Be=Xt):(Ue=so,Be=Jt),xa(Ki(Ue,Be),Tn(Be-Ue)),Ln||_a(0,J)),!Ln&&!Dn&&(_a(0,0),xa(0,0))}if(Vn._x=Ln,Vn._y=Dn,_==null){if(C){if(gg!=null){let[de,Me]=gn.scales;gn.values[0]=de!=null?ar(L.ori==0?Xt:Jt,de):null,gn.values[1]=Me!=null?ar(L.ori==1?Xt:Jt,Me):null}ba(Ld,i,Xt,Jt,O,Ce,P)}if(Qe){let de=C&&gn.setSeries,Me=ke.prox;Ss==null?Rr<=Me&&or(jr,ao,!0,de):Rr>Me?or(null,ao,!0,de):jr!=Ss&&or(jr,ao,!0,de)}}pe&&(fe.idx=P,bf()),S!==!1&&Un("setCursor")}let Qr=null;Object.defineProperty(i,"rect",{get(){return Qr==null&&va(!1),Qr}});function va(_=!1){_?Qr=null:(Qr=p.getBoundingClientRect(),Un("syncRect",Qr))}function og(_,S,C,P,G,J,ae){he._lock||qr&&_!=null&&_.movementX==0&&_.movementY==0||(Sf(_,S,C,P,G,J,ae,!1,_!=null),_!=null?Ms(null,!0,!0):Ms(S,!0,!1))}function Sf(_,S,C,P,G,J,ae,de,Me){if(Qr==null&&va(!1),je(_),_!=null)C=_.clientX-Qr.left,P=_.clientY-Qr.top;else{if(C<0||P<0){Xt=-10,Jt=-10;return}let[De,Ue]=gn.scales,Be=S.cursor.sync,[at,wt]=Be.values,[Mt,yt]=Be.scales,[qe,Xe]=gn.match,Zt=S.axes[0].side%2==1,sn=L.ori==0?O:Ce,On=L.ori==1?O:Ce,Ft=Zt?J:G,on=Zt?G:J,gi=Zt?P:C,ei=Zt?C:P;if(Mt!=null?C=qe(De,Mt)?a(at,M[De],sn,0):-10:C=sn*(gi/Ft),yt!=null?P=Xe(Ue,yt)?a(wt,M[Ue],On,0):-10:P=On*(ei/on),L.ori==1){let Ii=C;C=P,P=Ii}}Me&&(S==null||S.cursor.event.type==Ld)&&((C<=1||C>=O-1)&&(C=Cs(C,O)),(P<=1||P>=Ce-1)&&(P=Cs(P,Ce))),de?(eg=C,tg=P,[ro,so]=he.move(i,C,P)):(Xt=C,Jt=P)}let Mf={width:0,height:0,left:0,top:0};function Ef(){Kl(Mf,!1)}let ag,lg,cg,ug;function hg(_,S,C,P,G,J,ae){qr=!0,Ln=Dn=Vn._x=Vn._y=!1,Sf(_,S,C,P,G,J,ae,!0,!1),_!=null&&(St(Dd,kd,fg,!1),ba(qy,i,ro,so,O,Ce,null));let{left:de,top:Me,width:De,height:Ue}=Yt;ag=de,lg=Me,cg=De,ug=Ue}function fg(_,S,C,P,G,J,ae){qr=Vn._x=Vn._y=!1,Sf(_,S,C,P,G,J,ae,!1,!0);let{left:de,top:Me,width:De,height:Ue}=Yt,Be=De>0||Ue>0,at=ag!=de||lg!=Me||cg!=De||ug!=Ue;if(Be&&at&&Kl(Yt),Vn.setScale&&Be&&at){let wt=de,Mt=De,yt=Me,qe=Ue;if(L.ori==1&&(wt=Me,Mt=Ue,yt=de,qe=De),Ln&&Jr(w,ar(wt,w),ar(wt+Mt,w)),Dn)for(let Xe in M){let Zt=M[Xe];Xe!=w&&Zt.from==null&&Zt.min!=kt&&Jr(Xe,ar(yt+qe,Xe),ar(yt,Xe))}Ef()}else he.lock&&(he._lock=!he._lock,Ms(S,!0,_!=null));_!=null&&(En(Dd,kd),ba(Dd,i,Xt,Jt,O,Ce,null))}function vS(_,S,C,P,G,J,ae){if(he._lock)return;je(_);let de=qr;if(qr){let Me=!0,De=!0,Ue=10,Be,at;L.ori==0?(Be=Ln,at=Dn):(Be=Dn,at=Ln),Be&&at&&(Me=Xt<=Ue||Xt>=O-Ue,De=Jt<=Ue||Jt>=Ce-Ue),Be&&Me&&(Xt=Xt<ro?0:O),at&&De&&(Jt=Jt<so?0:Ce),Ms(null,!0,!0),qr=!1}Xt=-10,Jt=-10,ie.fill(null),Ms(null,!0,!0),de&&(qr=de)}function dg(_,S,C,P,G,J,ae){he._lock||(je(_),ya(),Ef(),_!=null&&ba(Qy,i,Xt,Jt,O,Ce,null))}function pg(){T.forEach(xA),U(i.width,i.height,!0)}Ls(Vc,Mo,pg);let lo={};lo.mousedown=hg,lo.mousemove=og,lo.mouseup=fg,lo.dblclick=dg,lo.setSeries=(_,S,C,P)=>{let G=gn.match[2];C=G(i,S,C),C!=-1&&or(C,P,!0,!1)},ge&&(St(qy,p,hg),St(Ld,p,og),St(Jy,p,_=>{je(_),va(!1)}),St(jy,p,vS),St(Qy,p,dg),Zd.add(i),i.syncRect=va);let $l=i.hooks=n.hooks||{};function Un(_,S,C){Qn?Dt.push([_,S,C]):_ in $l&&$l[_].forEach(P=>{P.call(null,i,S,C)})}(n.plugins||[]).forEach(_=>{for(let S in _.hooks)$l[S]=($l[S]||[]).concat(_.hooks[S])});let mg=(_,S,C)=>C,gn=vn({key:null,setSeries:!1,filters:{pub:u_,sub:u_},scales:[w,v[1]?v[1].scale:null],match:[h_,h_,mg],values:[null,null]},he.sync);gn.match.length==2&&gn.match.push(mg),he.sync=gn;let gg=gn.key,wf=ax(gg);function ba(_,S,C,P,G,J,ae){gn.filters.pub(_,S,C,P,G,J,ae)&&wf.pub(_,S,C,P,G,J,ae)}wf.sub(i);function bS(_,S,C,P,G,J,ae){gn.filters.sub(_,S,C,P,G,J,ae)&&lo[_](null,S,C,P,G,J,ae)}i.pub=bS;function SS(){wf.unsub(i),Zd.delete(i),Pn.clear(),zd(Vc,Mo,pg),c.remove(),xe?.remove(),Un("destroy")}i.destroy=SS;function Af(){Un("init",n,e),ga(e||n.data,!1),F[w]?_f(w,F[w]):ya(),re=Yt.show&&(Yt.width>0||Yt.height>0),te=pe=!0,U(n.width,n.height)}return v.forEach(js),T.forEach(Er),t?t instanceof HTMLElement?(t.appendChild(c),Af()):t(i,Af):Af(),i}Rn.assign=vn;Rn.fmtNum=ep;Rn.rangeNum=Gc;Rn.rangeLog=Wc;Rn.rangeAsinh=jd;Rn.orient=Us;Rn.pxRatio=At;Rn.join=uw;Rn.fmtDate=np,Rn.tzDate=bw;Rn.sync=ax;{Rn.addGap=iA,Rn.clipGaps=Zc;let n=Rn.paths={points:dx};n.linear=mx,n.stepped=oA,n.bars=aA,n.spline=cA}var xx={forceN:.02,torqueMnm:.2},vA=.08;function vx(...n){let e=1/0,t=-1/0;for(let i of n)for(let r=0;r<i.length;r++){let s=i[r];s<e&&(e=s),s>t&&(t=s)}return e<=t?[e,t]:null}function bx(n,e){let t=Math.min(n?.[0]??0,0),i=Math.max(n?.[1]??0,0);if(i-t<e){let s=(i+t)/2;[t,i]=[s-e/2,s+e/2]}let r=vA*(i-t);return[t-r,i+r]}function bA(n){let e=([i,r])=>-i/(r-i),t=Math.max(...n.map(e));return n.map(([i,r])=>e([i,r])<t?[-t*r/(1-t),r]:[i,r])}function qa(n,e){let[t,i]=bA([bx(vx(...n),xx.forceN),bx(vx(e),xx.torqueMnm)]);return{forceN:t,torqueMnm:i}}var Os={axial:"#d95f02",lateral:"#1b9e77",torque:"#7570b3",cursor:"#7b3294"};function Sx(n){return(e,t,i)=>{if(!Number.isFinite(t)||!Number.isFinite(i))return[0,1];if(!(i>t))return[t-.5,i+.5];let r=n*(i-t);return[t-r,i+r]}}function Mx(){return[{scale:"N",label:"force (N)",size:52,labelSize:20},{scale:"mNm",label:"torque (mN·m)",side:1,size:52,labelSize:20,grid:{show:!1}}]}var Ex={size:30,labelSize:18,labelGap:0};function wx(n){return{N:{range:()=>n().forceN},mNm:{range:()=>n().torqueMnm}}}function Ax(n,e){return t=>{let i=e();if(i===null)return;let r=Math.round(t.valToPos(i,n,!0)),{left:s,top:o,width:a,height:l}=t.bbox;if(r<s||r>s+a)return;let c=t.ctx;c.save(),c.strokeStyle=Os.cursor,c.lineWidth=1.5*devicePixelRatio,c.beginPath(),c.moveTo(r,o),c.lineTo(r,o+l),c.stroke(),c.restore()}}function Tx(n,...e){return[null,...e.map(i=>[n,i])]}var Jc=class{byTime;byDepth;cursor=null;timeLabel="time (s)";shown=null;timeRanges=qa([],[]);depthRanges=qa([],[]);constructor(e,t,i,r){this.byTime=new Rn({width:i,height:r,scales:{x:{time:!1,range:Sx(0)},...wx(()=>this.timeRanges)},axes:[{label:()=>this.timeLabel,...Ex},...Mx()],series:[{label:"time (s)"},{label:"axial (N)",scale:"N",stroke:Os.axial,width:1.5},{label:"lateral (N)",scale:"N",stroke:Os.lateral,width:1.5},{label:"torque (mN·m)",scale:"mNm",stroke:Os.torque,width:1.5}],cursor:{show:!1},legend:{live:!1},hooks:{draw:[Ax("x",()=>this.cursor?.timeS??null)]}},[[],[],[],[]],e);let s=(o,a,l)=>({label:o,stroke:l,width:1.5,facets:[{scale:"mm",auto:!0},{scale:a,auto:!0}],paths:Rn.paths.linear?.(),points:{show:!1}});this.byDepth=new Rn({mode:2,width:i,height:r,scales:{mm:{time:!1,range:Sx(.08)},...wx(()=>this.depthRanges)},axes:[{scale:"mm",label:"inserted depth (mm)",...Ex},...Mx()],series:[{},s("axial (N)","N",Os.axial),s("lateral (N)","N",Os.lateral),s("torque (mN·m)","mNm",Os.torque)],cursor:{show:!1},legend:{live:!1},hooks:{draw:[Ax("mm",()=>this.cursor?.depthMm??null)]}},Tx(new Float64Array(0),new Float64Array(0),new Float64Array(0),new Float64Array(0)),t)}show(e,t,i){let r=this.shown,s=r!==null&&r.history===e&&r.version===e.version&&r.windowS===t;if(this.cursor=i,s){this.byTime.redraw(!1,!1),this.byDepth.redraw(!1,!1);return}this.shown={history:e,version:e.version,windowS:t},this.timeLabel=t===null?"time (s)":`time (s), last ${t} s`;let o=e.recent.newestTimeS(),a=e.recent.window(t!==null&&o!==null?o-t:null);this.timeRanges=qa([a[ka],a[Va]],a[Ga]),this.byTime.setData([a[Pc],a[ka],a[Va],a[Ga]]);let l=e.trace.columns();this.depthRanges=qa([l[ka],l[Va]],l[Ga]),this.byDepth.setData(Tx(l[Uy],l[ka],l[Va],l[Ga]))}};function SA({polynomial:n,numTables:e}){let t=new Uint32Array(256*e);for(let i=0;i<256;i++){let r=i;r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,r=(r&1)*n^r>>>1,t[i]=r}for(let i=256;i<t.length;i++){let r=t[i-256];t[i]=t[r&255]^r>>>8}return t}var dr=SA({polynomial:3988292384,numTables:8});function cp(){return-1}function up(n,e){let t=e.byteLength,i=new DataView(e.buffer,e.byteOffset,t),r=n,s=0,o=-i.byteOffset&3;for(;s<o&&s<t;s++)r=dr[(r^i.getUint8(s))&255]^r>>>8;if(s===t)return r;s=o;let a=t-s;for(;a>=8;s+=8,a-=8){r^=i.getUint32(s,!0);let l=i.getUint32(s+4,!0);r=dr[0*256+(l>>>24&255)]^dr[1*256+(l>>>16&255)]^dr[2*256+(l>>>8&255)]^dr[3*256+(l>>>0&255)]^dr[4*256+(r>>>24&255)]^dr[5*256+(r>>>16&255)]^dr[6*256+(r>>>8&255)]^dr[7*256+(r>>>0&255)]}for(let l=s;l<t;l++)r=dr[(r^i.getUint8(l))&255]^r>>>8;return r}function hp(n){return(n^-1)>>>0}function Fs(n){return hp(up(cp(),n))}var Ut=function(n,e,t,i){function r(s){return s instanceof t?s:new t(function(o){o(s)})}return new(t||(t=Promise))(function(s,o){function a(u){try{c(i.next(u))}catch(h){o(h)}}function l(u){try{c(i.throw(u))}catch(h){o(h)}}function c(u){u.done?s(u.value):r(u.value).then(a,l)}c((i=i.apply(n,e||[])).next())})},Ct=function(n,e){var t={label:0,sent:function(){if(s[0]&1)throw s[1];return s[1]},trys:[],ops:[]},i,r,s,o=Object.create((typeof Iterator=="function"?Iterator:Object).prototype);return o.next=a(0),o.throw=a(1),o.return=a(2),typeof Symbol=="function"&&(o[Symbol.iterator]=function(){return this}),o;function a(c){return function(u){return l([c,u])}}function l(c){if(i)throw new TypeError("Generator is already executing.");for(;o&&(o=0,c[0]&&(t=0)),t;)try{if(i=1,r&&(s=c[0]&2?r.return:c[0]?r.throw||((s=r.return)&&s.call(r),0):r.next)&&!(s=s.call(r,c[1])).done)return s;switch(r=0,s&&(c=[c[0]&2,s.value]),c[0]){case 0:case 1:s=c;break;case 4:return t.label++,{value:c[1],done:!1};case 5:t.label++,r=c[1],c=[0];continue;case 7:c=t.ops.pop(),t.trys.pop();continue;default:if(s=t.trys,!(s=s.length>0&&s[s.length-1])&&(c[0]===6||c[0]===2)){t=0;continue}if(c[0]===3&&(!s||c[1]>s[0]&&c[1]<s[3])){t.label=c[1];break}if(c[0]===6&&t.label<s[1]){t.label=s[1],s=c;break}if(s&&t.label<s[2]){t.label=s[2],t.ops.push(c);break}s[2]&&t.ops.pop(),t.trys.pop();continue}c=e.call(n,t)}catch(u){c=[6,u],r=0}finally{i=s=0}if(c[0]&5)throw c[1];return{value:c[0]?c[1]:void 0,done:!0}}},Si=function(n,e){var t=typeof Symbol=="function"&&n[Symbol.iterator];if(!t)return n;var i=t.call(n),r,s=[],o;try{for(;(e===void 0||e-- >0)&&!(r=i.next()).done;)s.push(r.value)}catch(a){o={error:a}}finally{try{r&&!r.done&&(t=i.return)&&t.call(i)}finally{if(o)throw o.error}}return s},Li=function(n,e,t){if(t||arguments.length===2)for(var i=0,r=e.length,s;i<r;i++)(s||!(i in e))&&(s||(s=Array.prototype.slice.call(e,0,i)),s[i]=e[i]);return n.concat(s||Array.prototype.slice.call(e))},Rx=function(n){var e=typeof Symbol=="function"&&Symbol.iterator,t=e&&n[e],i=0;if(t)return t.call(n);if(n&&typeof n.length=="number")return{next:function(){return n&&i>=n.length&&(n=void 0),{value:n&&n[i++],done:!n}}};throw new TypeError(e?"Object is not iterable.":"Symbol.iterator is not defined.")},$U=(function(){function n(e){e===void 0&&(e=n.minComparator);var t=this;this.compare=e,this.heapArray=[],this._limit=0,this.offer=this.add,this.element=this.peek,this.poll=this.pop,this._invertedCompare=function(i,r){return t.compare(i,r).then(function(s){return-1*s})}}return n.getChildrenIndexOf=function(e){return[e*2+1,e*2+2]},n.getParentIndexOf=function(e){if(e<=0)return-1;var t=e%2?1:2;return Math.floor((e-t)/2)},n.getSiblingIndexOf=function(e){if(e<=0)return-1;var t=e%2?1:-1;return e+t},n.minComparator=function(e,t){return Ut(this,void 0,void 0,function(){return Ct(this,function(i){return e>t?[2,1]:e<t?[2,-1]:[2,0]})})},n.maxComparator=function(e,t){return Ut(this,void 0,void 0,function(){return Ct(this,function(i){return t>e?[2,1]:t<e?[2,-1]:[2,0]})})},n.minComparatorNumber=function(e,t){return Ut(this,void 0,void 0,function(){return Ct(this,function(i){return[2,e-t]})})},n.maxComparatorNumber=function(e,t){return Ut(this,void 0,void 0,function(){return Ct(this,function(i){return[2,t-e]})})},n.defaultIsEqual=function(e,t){return Ut(this,void 0,void 0,function(){return Ct(this,function(i){return[2,e===t]})})},n.print=function(e){function t(u){var h=n.getParentIndexOf(u);return Math.floor(Math.log2(h+1))}function i(u,h){for(var f="";h>0;--h)f+=u;return f}for(var r=0,s=[],o=t(e.length-1)+2,a=0;r<e.length;){var l=t(r)+1;r===0&&(l=0);var c=String(e.get(r));c.length>a&&(a=c.length),s[l]=s[l]||[],s[l].push(c),r+=1}return s.map(function(u,h){var f=Math.pow(2,o-h)-1;return i(" ",Math.floor(f/2)*a)+u.map(function(d){var p=(a-d.length)/2;return i(" ",Math.ceil(p))+d+i(" ",Math.floor(p))}).join(i(" ",f*a))}).join(`
`)},n.heapify=function(e,t){return Ut(this,void 0,void 0,function(){var i;return Ct(this,function(r){switch(r.label){case 0:return i=new n(t),i.heapArray=e,[4,i.init()];case 1:return r.sent(),[2,i]}})})},n.heappop=function(e,t){var i=new n(t);return i.heapArray=e,i.pop()},n.heappush=function(e,t,i){return Ut(this,void 0,void 0,function(){var r;return Ct(this,function(s){switch(s.label){case 0:return r=new n(i),r.heapArray=e,[4,r.push(t)];case 1:return s.sent(),[2]}})})},n.heappushpop=function(e,t,i){var r=new n(i);return r.heapArray=e,r.pushpop(t)},n.heapreplace=function(e,t,i){var r=new n(i);return r.heapArray=e,r.replace(t)},n.heaptop=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.top(t)},n.heapbottom=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.bottom(t)},n.nlargest=function(e,t,i){return Ut(this,void 0,void 0,function(){var r;return Ct(this,function(s){switch(s.label){case 0:return r=new n(i),r.heapArray=Li([],Si(t),!1),[4,r.init()];case 1:return s.sent(),[2,r.top(e)]}})})},n.nsmallest=function(e,t,i){return Ut(this,void 0,void 0,function(){var r;return Ct(this,function(s){switch(s.label){case 0:return r=new n(i),r.heapArray=Li([],Si(t),!1),[4,r.init()];case 1:return s.sent(),[2,r.bottom(e)]}})})},n.prototype.add=function(e){return Ut(this,void 0,void 0,function(){return Ct(this,function(t){switch(t.label){case 0:return[4,this._sortNodeUp(this.heapArray.push(e)-1)];case 1:return t.sent(),this._applyLimit(),[2,!0]}})})},n.prototype.addAll=function(e){return Ut(this,void 0,void 0,function(){var t,i,r;return Ct(this,function(s){switch(s.label){case 0:t=this.length,(r=this.heapArray).push.apply(r,Li([],Si(e),!1)),i=this.length,s.label=1;case 1:return t<i?[4,this._sortNodeUp(t)]:[3,4];case 2:s.sent(),s.label=3;case 3:return++t,[3,1];case 4:return this._applyLimit(),[2,!0]}})})},n.prototype.bottom=function(){return Ut(this,arguments,void 0,function(e){return e===void 0&&(e=1),Ct(this,function(t){return this.heapArray.length===0||e<=0?[2,[]]:this.heapArray.length===1?[2,[this.heapArray[0]]]:e>=this.heapArray.length?[2,Li([],Si(this.heapArray),!1)]:[2,this._bottomN_push(~~e)]})})},n.prototype.check=function(){return Ut(this,void 0,void 0,function(){var e,t,i,r,s,o,a,l,c;return Ct(this,function(u){switch(u.label){case 0:e=0,u.label=1;case 1:if(!(e<this.heapArray.length))return[3,10];t=this.heapArray[e],i=this.getChildrenOf(e),u.label=2;case 2:u.trys.push([2,7,8,9]),r=(l=void 0,Rx(i)),s=r.next(),u.label=3;case 3:return s.done?[3,6]:(o=s.value,[4,this.compare(t,o)]);case 4:if(u.sent()>0)return[2,t];u.label=5;case 5:return s=r.next(),[3,3];case 6:return[3,9];case 7:return a=u.sent(),l={error:a},[3,9];case 8:try{s&&!s.done&&(c=r.return)&&c.call(r)}finally{if(l)throw l.error}return[7];case 9:return++e,[3,1];case 10:return[2]}})})},n.prototype.clear=function(){this.heapArray=[]},n.prototype.clone=function(){var e=new n(this.comparator());return e.heapArray=this.toArray(),e._limit=this._limit,e},n.prototype.comparator=function(){return this.compare},n.prototype.contains=function(e){return Ut(this,arguments,void 0,function(t,i){var r,s,o,a,l,c;return i===void 0&&(i=n.defaultIsEqual),Ct(this,function(u){switch(u.label){case 0:u.trys.push([0,5,6,7]),r=Rx(this.heapArray),s=r.next(),u.label=1;case 1:return s.done?[3,4]:(o=s.value,[4,i(o,t)]);case 2:if(u.sent())return[2,!0];u.label=3;case 3:return s=r.next(),[3,1];case 4:return[3,7];case 5:return a=u.sent(),l={error:a},[3,7];case 6:try{s&&!s.done&&(c=r.return)&&c.call(r)}finally{if(l)throw l.error}return[7];case 7:return[2,!1]}})})},n.prototype.init=function(e){return Ut(this,void 0,void 0,function(){var t;return Ct(this,function(i){switch(i.label){case 0:e&&(this.heapArray=Li([],Si(e),!1)),t=n.getParentIndexOf(this.length-1),i.label=1;case 1:return t>=0?[4,this._sortNodeDown(t)]:[3,4];case 2:i.sent(),i.label=3;case 3:return--t,[3,1];case 4:return this._applyLimit(),[2]}})})},n.prototype.isEmpty=function(){return this.length===0},n.prototype.leafs=function(){if(this.heapArray.length===0)return[];var e=n.getParentIndexOf(this.heapArray.length-1);return this.heapArray.slice(e+1)},Object.defineProperty(n.prototype,"length",{get:function(){return this.heapArray.length},enumerable:!1,configurable:!0}),Object.defineProperty(n.prototype,"limit",{get:function(){return this._limit},set:function(e){this._limit=~~e,this._applyLimit()},enumerable:!1,configurable:!0}),n.prototype.peek=function(){return this.heapArray[0]},n.prototype.pop=function(){return Ut(this,void 0,void 0,function(){var e;return Ct(this,function(t){return e=this.heapArray.pop(),this.length>0&&e!==void 0?[2,this.replace(e)]:[2,e]})})},n.prototype.push=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];return Ut(this,void 0,void 0,function(){return Ct(this,function(i){return e.length<1?[2,!1]:e.length===1?[2,this.add(e[0])]:[2,this.addAll(e)]})})},n.prototype.pushpop=function(e){return Ut(this,void 0,void 0,function(){var t;return Ct(this,function(i){switch(i.label){case 0:return[4,this.compare(this.heapArray[0],e)];case 1:return i.sent()<0?(t=Si([this.heapArray[0],e],2),e=t[0],this.heapArray[0]=t[1],[4,this._sortNodeDown(0)]):[3,3];case 2:i.sent(),i.label=3;case 3:return[2,e]}})})},n.prototype.remove=function(e){return Ut(this,arguments,void 0,function(t,i){var r,s,o,a=this;return i===void 0&&(i=n.defaultIsEqual),Ct(this,function(l){switch(l.label){case 0:return this.heapArray.length?t!==void 0?[3,2]:[4,this.pop()]:[2,!1];case 1:return l.sent(),[2,!0];case 2:r=[0],l.label=3;case 3:return r.length?(s=r.shift(),[4,i(this.heapArray[s],t)]):[3,13];case 4:return l.sent()?s!==0?[3,6]:[4,this.pop()]:[3,11];case 5:return l.sent(),[3,10];case 6:return s!==this.heapArray.length-1?[3,7]:(this.heapArray.pop(),[3,10]);case 7:return this.heapArray.splice(s,1,this.heapArray.pop()),[4,this._sortNodeUp(s)];case 8:return l.sent(),[4,this._sortNodeDown(s)];case 9:l.sent(),l.label=10;case 10:return[2,!0];case 11:o=n.getChildrenIndexOf(s).filter(function(c){return c<a.heapArray.length}),r.push.apply(r,Li([],Si(o),!1)),l.label=12;case 12:return[3,3];case 13:return[2,!1]}})})},n.prototype.replace=function(e){return Ut(this,void 0,void 0,function(){var t;return Ct(this,function(i){switch(i.label){case 0:return t=this.heapArray[0],this.heapArray[0]=e,[4,this._sortNodeDown(0)];case 1:return i.sent(),[2,t]}})})},n.prototype.size=function(){return this.length},n.prototype.top=function(){return Ut(this,arguments,void 0,function(e){return e===void 0&&(e=1),Ct(this,function(t){return this.heapArray.length===0||e<=0?[2,[]]:this.heapArray.length===1||e===1?[2,[this.heapArray[0]]]:e>=this.heapArray.length?[2,Li([],Si(this.heapArray),!1)]:[2,this._topN_push(~~e)]})})},n.prototype.toArray=function(){return Li([],Si(this.heapArray),!1)},n.prototype.toString=function(){return this.heapArray.toString()},n.prototype.get=function(e){return this.heapArray[e]},n.prototype.getChildrenOf=function(e){var t=this;return n.getChildrenIndexOf(e).map(function(i){return t.heapArray[i]}).filter(function(i){return i!==void 0})},n.prototype.getParentOf=function(e){var t=n.getParentIndexOf(e);return this.heapArray[t]},n.prototype[Symbol.iterator]=function(){return Ct(this,function(e){switch(e.label){case 0:return this.length?[4,this.pop()]:[3,2];case 1:return e.sent(),[3,0];case 2:return[2]}})},n.prototype.iterator=function(){return this},n.prototype._applyLimit=function(){if(this._limit&&this._limit<this.heapArray.length)for(var e=this.heapArray.length-this._limit;e;)this.heapArray.pop(),--e},n.prototype._bottomN_push=function(e){return Ut(this,void 0,void 0,function(){var t,i,r,s,a,o,a;return Ct(this,function(l){switch(l.label){case 0:return t=new n(this.compare),t.limit=e,t.heapArray=this.heapArray.slice(-e),[4,t.init()];case 1:for(l.sent(),i=this.heapArray.length-1-e,r=n.getParentIndexOf(i),s=[],a=i;a>r;--a)s.push(a);o=this.heapArray,l.label=2;case 2:return s.length?(a=s.shift(),[4,this.compare(o[a],t.peek())]):[3,6];case 3:return l.sent()>0?[4,t.replace(o[a])]:[3,5];case 4:l.sent(),a%2&&s.push(n.getParentIndexOf(a)),l.label=5;case 5:return[3,2];case 6:return[2,t.toArray()]}})})},n.prototype._moveNode=function(e,t){var i=this.heapArray[e];this.heapArray[e]=this.heapArray[t],this.heapArray[t]=i},n.prototype._sortNodeDown=function(e){return Ut(this,void 0,void 0,function(){var t,i,r,s,o,a,l;return Ct(this,function(c){switch(c.label){case 0:t=this.heapArray.length,i=e,r=this.heapArray[e],s=2*e+1,c.label=1;case 1:return s<t?(o=s+1,l=o>=t,l?[3,3]:[4,this.compare(this.heapArray[s],this.heapArray[o])]):[3,5];case 2:l=c.sent()<0,c.label=3;case 3:return a=l?s:o,[4,this.compare(this.heapArray[a],r)];case 4:if(c.sent()<0)this.heapArray[e]=this.heapArray[a],e=a,s=2*e+1;else return[3,5];return[3,1];case 5:return e!==i&&(this.heapArray[e]=r),[2]}})})},n.prototype._sortNodeUp=function(e){return Ut(this,void 0,void 0,function(){var t,i,r;return Ct(this,function(s){switch(s.label){case 0:t=this.heapArray[e],i=e,s.label=1;case 1:return e>0?(r=n.getParentIndexOf(e),[4,this.compare(t,this.heapArray[r])]):[3,3];case 2:if(s.sent()<0)this.heapArray[e]=this.heapArray[r],e=r;else return[3,3];return[3,1];case 3:return e!==i&&(this.heapArray[e]=t),[2]}})})},n.prototype._topN_push=function(e){return Ut(this,void 0,void 0,function(){var t,i,r,s;return Ct(this,function(o){switch(o.label){case 0:t=new n(this._invertedCompare),t.limit=e,i=[0],r=this.heapArray,o.label=1;case 1:return i.length?(s=i.shift(),s<r.length?t.length<e?[4,t.push(r[s])]:[3,3]:[3,6]):[3,7];case 2:return o.sent(),i.push.apply(i,Li([],Si(n.getChildrenIndexOf(s)),!1)),[3,6];case 3:return[4,this.compare(r[s],t.peek())];case 4:return o.sent()<0?[4,t.replace(r[s])]:[3,6];case 5:o.sent(),i.push.apply(i,Li([],Si(n.getChildrenIndexOf(s)),!1)),o.label=6;case 6:return[3,1];case 7:return[2,t.toArray()]}})})},n.prototype._topN_fill=function(e){return Ut(this,void 0,void 0,function(){var t,i,r,s,o,o;return Ct(this,function(a){switch(a.label){case 0:return t=this.heapArray,i=new n(this._invertedCompare),i.limit=e,i.heapArray=t.slice(0,e),[4,i.init()];case 1:for(a.sent(),r=n.getParentIndexOf(e-1)+1,s=[],o=r;o<e;++o)s.push.apply(s,Li([],Si(n.getChildrenIndexOf(o).filter(function(l){return l<t.length})),!1));(e-1)%2&&s.push(e),a.label=2;case 2:return s.length?(o=s.shift(),o<t.length?[4,this.compare(t[o],i.peek())]:[3,5]):[3,6];case 3:return a.sent()<0?[4,i.replace(t[o])]:[3,5];case 4:a.sent(),s.push.apply(s,Li([],Si(n.getChildrenIndexOf(o)),!1)),a.label=5;case 5:return[3,2];case 6:return[2,i.toArray()]}})})},n.prototype._topN_heap=function(e){return Ut(this,void 0,void 0,function(){var t,i,r,s,o;return Ct(this,function(a){switch(a.label){case 0:t=this.clone(),i=[],r=0,a.label=1;case 1:return r<e?(o=(s=i).push,[4,t.pop()]):[3,4];case 2:o.apply(s,[a.sent()]),a.label=3;case 3:return++r,[3,1];case 4:return[2,i]}})})},n.prototype._topIdxOf=function(e){return Ut(this,void 0,void 0,function(){var t,i,r,s;return Ct(this,function(o){switch(o.label){case 0:if(!e.length)return[2,-1];t=0,i=e[t],r=1,o.label=1;case 1:return r<e.length?[4,this.compare(e[r],i)]:[3,4];case 2:s=o.sent(),s<0&&(t=r,i=e[r]),o.label=3;case 3:return++r,[3,1];case 4:return[2,t]}})})},n.prototype._topOf=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];return Ut(this,void 0,void 0,function(){var i;return Ct(this,function(r){switch(r.label){case 0:return i=new n(this.compare),[4,i.init(e)];case 1:return r.sent(),[2,i.peek()]}})})},n})(),MA=function(n,e){var t={label:0,sent:function(){if(s[0]&1)throw s[1];return s[1]},trys:[],ops:[]},i,r,s,o=Object.create((typeof Iterator=="function"?Iterator:Object).prototype);return o.next=a(0),o.throw=a(1),o.return=a(2),typeof Symbol=="function"&&(o[Symbol.iterator]=function(){return this}),o;function a(c){return function(u){return l([c,u])}}function l(c){if(i)throw new TypeError("Generator is already executing.");for(;o&&(o=0,c[0]&&(t=0)),t;)try{if(i=1,r&&(s=c[0]&2?r.return:c[0]?r.throw||((s=r.return)&&s.call(r),0):r.next)&&!(s=s.call(r,c[1])).done)return s;switch(r=0,s&&(c=[c[0]&2,s.value]),c[0]){case 0:case 1:s=c;break;case 4:return t.label++,{value:c[1],done:!1};case 5:t.label++,r=c[1],c=[0];continue;case 7:c=t.ops.pop(),t.trys.pop();continue;default:if(s=t.trys,!(s=s.length>0&&s[s.length-1])&&(c[0]===6||c[0]===2)){t=0;continue}if(c[0]===3&&(!s||c[1]>s[0]&&c[1]<s[3])){t.label=c[1];break}if(c[0]===6&&t.label<s[1]){t.label=s[1],s=c;break}if(s&&t.label<s[2]){t.label=s[2],t.ops.push(c);break}s[2]&&t.ops.pop(),t.trys.pop();continue}c=e.call(n,t)}catch(u){c=[6,u],r=0}finally{i=s=0}if(c[0]&5)throw c[1];return{value:c[0]?c[1]:void 0,done:!0}}},Yn=function(n,e){var t=typeof Symbol=="function"&&n[Symbol.iterator];if(!t)return n;var i=t.call(n),r,s=[],o;try{for(;(e===void 0||e-- >0)&&!(r=i.next()).done;)s.push(r.value)}catch(a){o={error:a}}finally{try{r&&!r.done&&(t=i.return)&&t.call(i)}finally{if(o)throw o.error}}return s},si=function(n,e,t){if(t||arguments.length===2)for(var i=0,r=e.length,s;i<r;i++)(s||!(i in e))&&(s||(s=Array.prototype.slice.call(e,0,i)),s[i]=e[i]);return n.concat(s||Array.prototype.slice.call(e))};var EA=(function(){function n(e){e===void 0&&(e=n.minComparator);var t=this;this.compare=e,this.heapArray=[],this._limit=0,this.offer=this.add,this.element=this.peek,this.poll=this.pop,this.removeAll=this.clear,this._invertedCompare=function(i,r){return-1*t.compare(i,r)}}return n.getChildrenIndexOf=function(e){return[e*2+1,e*2+2]},n.getParentIndexOf=function(e){return e<=0?-1:e-1>>1},n.getSiblingIndexOf=function(e){if(e<=0)return-1;var t=e%2?1:-1;return e+t},n.minComparator=function(e,t){return e>t?1:e<t?-1:0},n.maxComparator=function(e,t){return t>e?1:t<e?-1:0},n.minComparatorNumber=function(e,t){return e-t},n.maxComparatorNumber=function(e,t){return t-e},n.defaultIsEqual=function(e,t){return e===t},n.print=function(e){function t(u){var h=n.getParentIndexOf(u);return Math.floor(Math.log2(h+1))}function i(u,h){for(var f="";h>0;--h)f+=u;return f}for(var r=0,s=[],o=t(e.length-1)+2,a=0;r<e.length;){var l=t(r)+1;r===0&&(l=0);var c=String(e.get(r));c.length>a&&(a=c.length),s[l]=s[l]||[],s[l].push(c),r+=1}return s.map(function(u,h){var f=Math.pow(2,o-h)-1;return i(" ",Math.floor(f/2)*a)+u.map(function(d){var p=(a-d.length)/2;return i(" ",Math.ceil(p))+d+i(" ",Math.floor(p))}).join(i(" ",f*a))}).join(`
`)},n.heapify=function(e,t){var i=new n(t);return i.heapArray=e,i.init(),i},n.heappop=function(e,t){var i=new n(t);return i.heapArray=e,i.pop()},n.heappush=function(e,t,i){var r=new n(i);r.heapArray=e,r.push(t)},n.heappushpop=function(e,t,i){var r=new n(i);return r.heapArray=e,r.pushpop(t)},n.heapreplace=function(e,t,i){var r=new n(i);return r.heapArray=e,r.replace(t)},n.heaptop=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.top(t)},n.heapbottom=function(e,t,i){t===void 0&&(t=1);var r=new n(i);return r.heapArray=e,r.bottom(t)},n.nlargest=function(e,t,i){var r=new n(i);return r.heapArray=si([],Yn(t),!1),r.init(),r.top(e)},n.nsmallest=function(e,t,i){var r=new n(i);return r.heapArray=si([],Yn(t),!1),r.init(),r.bottom(e)},n.prototype.add=function(e){return this._sortNodeUp(this.heapArray.push(e)-1),this._applyLimit(),!0},n.prototype.addAll=function(e){var t,i=this.length;(t=this.heapArray).push.apply(t,si([],Yn(e),!1));for(var r=this.length;i<r;++i)this._sortNodeUp(i);return this._applyLimit(),!0},n.prototype.bottom=function(e){return e===void 0&&(e=1),this.heapArray.length===0||e<=0?[]:this.heapArray.length===1?[this.heapArray[0]]:e>=this.heapArray.length?si([],Yn(this.heapArray),!1):this._bottomN_push(~~e)},n.prototype.check=function(){var e=this;return this.heapArray.find(function(t,i){return!!e.getChildrenOf(i).find(function(r){return e.compare(t,r)>0})})},n.prototype.clear=function(){this.heapArray=[]},n.prototype.clone=function(){var e=new n(this.comparator());return e.heapArray=this.toArray(),e._limit=this._limit,e},n.prototype.comparator=function(){return this.compare},n.prototype.contains=function(e,t){return t===void 0&&(t=n.defaultIsEqual),this.indexOf(e,t)!==-1},n.prototype.init=function(e){e&&(this.heapArray=si([],Yn(e),!1));for(var t=n.getParentIndexOf(this.length-1);t>=0;--t)this._sortNodeDown(t);this._applyLimit()},n.prototype.isEmpty=function(){return this.length===0},n.prototype.indexOf=function(e,t){if(t===void 0&&(t=n.defaultIsEqual),this.heapArray.length===0)return-1;for(var i=[],r=0;r<this.heapArray.length;){var s=this.heapArray[r];if(t(s,e))return r;this.compare(s,e)<=0&&i.push.apply(i,si([],Yn(n.getChildrenIndexOf(r)),!1)),r=i.shift()||this.heapArray.length}return-1},n.prototype.indexOfEvery=function(e,t){if(t===void 0&&(t=n.defaultIsEqual),this.heapArray.length===0)return[];for(var i=[],r=[],s=0;s<this.heapArray.length;){var o=this.heapArray[s];t(o,e)?(r.push(s),i.push.apply(i,si([],Yn(n.getChildrenIndexOf(s)),!1))):this.compare(o,e)<=0&&i.push.apply(i,si([],Yn(n.getChildrenIndexOf(s)),!1)),s=i.shift()||this.heapArray.length}return r},n.prototype.leafs=function(){if(this.heapArray.length===0)return[];var e=n.getParentIndexOf(this.heapArray.length-1);return this.heapArray.slice(e+1)},Object.defineProperty(n.prototype,"length",{get:function(){return this.heapArray.length},enumerable:!1,configurable:!0}),Object.defineProperty(n.prototype,"limit",{get:function(){return this._limit},set:function(e){e<0||isNaN(e)?this._limit=0:this._limit=~~e,this._applyLimit()},enumerable:!1,configurable:!0}),n.prototype.setLimit=function(e){return this.limit=e,e<0||isNaN(e)?NaN:this._limit},n.prototype.peek=function(){return this.heapArray[0]},n.prototype.pop=function(){var e=this.heapArray.pop();return this.length>0&&e!==void 0?this.replace(e):e},n.prototype.push=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];return e.length<1?!1:e.length===1?this.add(e[0]):this.addAll(e)},n.prototype.pushpop=function(e){var t;return this.compare(this.heapArray[0],e)<0&&(t=Yn([this.heapArray[0],e],2),e=t[0],this.heapArray[0]=t[1],this._sortNodeDown(0)),e},n.prototype.remove=function(e,t){var i=this;if(t===void 0&&(t=n.defaultIsEqual),!this.heapArray.length)return!1;if(e===void 0)return this.pop(),!0;for(var r=[0];r.length;){var s=r.shift();if(t(this.heapArray[s],e))return s===0?this.pop():s===this.heapArray.length-1?this.heapArray.pop():(this.heapArray.splice(s,1,this.heapArray.pop()),this._sortNodeUp(s),this._sortNodeDown(s)),!0;if(this.compare(this.heapArray[s],e)<=0){var o=n.getChildrenIndexOf(s).filter(function(a){return a<i.heapArray.length});r.push.apply(r,si([],Yn(o),!1))}}return!1},n.prototype.replace=function(e){var t=this.heapArray[0];return this.heapArray[0]=e,this._sortNodeDown(0),t},n.prototype.size=function(){return this.length},n.prototype.top=function(e){return e===void 0&&(e=1),this.heapArray.length===0||e<=0?[]:this.heapArray.length===1||e===1?[this.heapArray[0]]:e>=this.heapArray.length?si([],Yn(this.heapArray),!1):this._topN_push(~~e)},n.prototype.toArray=function(){return si([],Yn(this.heapArray),!1)},n.prototype.toString=function(){return this.heapArray.toString()},n.prototype.get=function(e){return this.heapArray[e]},n.prototype.getChildrenOf=function(e){var t=this;return n.getChildrenIndexOf(e).map(function(i){return t.heapArray[i]}).filter(function(i){return i!==void 0})},n.prototype.getParentOf=function(e){var t=n.getParentIndexOf(e);return this.heapArray[t]},n.prototype[Symbol.iterator]=function(){return MA(this,function(e){switch(e.label){case 0:return this.length?[4,this.pop()]:[3,2];case 1:return e.sent(),[3,0];case 2:return[2]}})},n.prototype.iterator=function(){return this.toArray()},n.prototype._applyLimit=function(){if(this._limit>0&&this._limit<this.heapArray.length)for(var e=this.heapArray.length-this._limit;e;)this.heapArray.pop(),--e},n.prototype._bottomN_push=function(e){var t=new n(this.compare);t.limit=e,t.heapArray=this.heapArray.slice(-e),t.init();for(var i=this.heapArray.length-1-e,r=n.getParentIndexOf(i),s=[],o=i;o>r;--o)s.push(o);for(var a=this.heapArray;s.length;){var o=s.shift();this.compare(a[o],t.peek())>0&&(t.replace(a[o]),o%2&&s.push(n.getParentIndexOf(o)))}return t.toArray()},n.prototype._moveNode=function(e,t){var i=this.heapArray[e];this.heapArray[e]=this.heapArray[t],this.heapArray[t]=i},n.prototype._sortNodeDown=function(e){for(var t=this.heapArray.length,i=e,r=this.heapArray[e],s=2*e+1;s<t;){var o=s+1,a=o>=t||this.compare(this.heapArray[s],this.heapArray[o])<0?s:o;if(this.compare(this.heapArray[a],r)<0)this.heapArray[e]=this.heapArray[a],e=a,s=2*e+1;else break}e!==i&&(this.heapArray[e]=r)},n.prototype._sortNodeUp=function(e){for(var t=this.heapArray[e],i=e;e>0;){var r=n.getParentIndexOf(e);if(this.compare(t,this.heapArray[r])<0)this.heapArray[e]=this.heapArray[r],e=r;else break}e!==i&&(this.heapArray[e]=t)},n.prototype._topN_push=function(e){var t=new n(this._invertedCompare);t.limit=e;for(var i=[0],r=this.heapArray;i.length;){var s=i.shift();s<r.length&&(t.length<e?(t.push(r[s]),i.push.apply(i,si([],Yn(n.getChildrenIndexOf(s)),!1))):this.compare(r[s],t.peek())<0&&(t.replace(r[s]),i.push.apply(i,si([],Yn(n.getChildrenIndexOf(s)),!1))))}return t.toArray()},n.prototype._topN_fill=function(e){var t=this.heapArray,i=new n(this._invertedCompare);i.limit=e,i.heapArray=t.slice(0,e),i.init();for(var r=n.getParentIndexOf(e-1)+1,s=[],o=r;o<e;++o)s.push.apply(s,si([],Yn(n.getChildrenIndexOf(o).filter(function(a){return a<t.length})),!1));for((e-1)%2&&s.push(e);s.length;){var o=s.shift();o<t.length&&this.compare(t[o],i.peek())<0&&(i.replace(t[o]),s.push.apply(s,si([],Yn(n.getChildrenIndexOf(o)),!1)))}return i.toArray()},n.prototype._topN_heap=function(e){for(var t=this.clone(),i=[],r=0;r<e;++r)i.push(t.pop());return i},n.prototype._topIdxOf=function(e){if(!e.length)return-1;for(var t=0,i=e[t],r=1;r<e.length;++r){var s=this.compare(e[r],i);s<0&&(t=r,i=e[r])}return t},n.prototype._topOf=function(){for(var e=[],t=0;t<arguments.length;t++)e[t]=arguments[t];var i=new n(this.compare);return i.init(e),i.peek()},n})();var Ix=typeof DataView.prototype.getBigUint64=="function"?DataView.prototype.getBigUint64:function(n,e){let t=e===!0?this.getUint32(n,e):this.getUint32(n+4,e),i=e===!0?this.getUint32(n+4,e):this.getUint32(n,e);return BigInt(i)<<32n|BigInt(t)};var wA=new TextDecoder,rs=class{#t;#e;offset;constructor(e,t=0){this.#t=e,this.#e=new Uint8Array(e.buffer,e.byteOffset,e.byteLength),this.offset=t}reset(e,t=0){this.#t=e,this.#e=new Uint8Array(e.buffer,e.byteOffset,e.byteLength),this.offset=t}bytesRemaining(){return this.#e.length-this.offset}uint8(){let e=this.#t.getUint8(this.offset);return this.offset+=1,e}uint16(){let e=this.#t.getUint16(this.offset,!0);return this.offset+=2,e}uint32(){let e=this.#t.getUint32(this.offset,!0);return this.offset+=4,e}uint64(){let e=Ix.call(this.#t,this.offset,!0);return this.offset+=8,e}string(){let e=this.uint32();if(e===0)return"";if(e>this.bytesRemaining())throw new Error(`String length ${e} exceeds bounds of buffer`);return wA.decode(this.u8ArrayBorrow(e))}keyValuePairs(e,t){let i=this.uint32();if(this.offset+i>this.#t.byteLength)throw new Error(`Key-value pairs length ${i} exceeds bounds of buffer`);let r=[],s=this.offset+i;try{for(;this.offset<s;)r.push([e(this),t(this)])}catch(o){throw new Error(`Error reading key-value pairs: ${o.message}`)}if(this.offset!==s)throw new Error(`Key-value pairs length (${this.offset-s+i}) greater than expected (${i})`);return r}map(e,t){let i=this.uint32();if(this.offset+i>this.#t.byteLength)throw new Error(`Map length ${i} exceeds bounds of buffer`);let r=new Map,s=this.offset+i;try{for(;this.offset<s;){let o=e(this),a=t(this),l=r.get(o);if(l!=null)throw new Error(`Duplicate key ${String(o)} (${String(l)} vs ${String(a)})`);r.set(o,a)}}catch(o){throw new Error(`Error reading map: ${o.message}`)}if(this.offset!==s)throw new Error(`Map length (${this.offset-s+i}) greater than expected (${i})`);return r}u8ArrayBorrow(e){let t=this.#e.subarray(this.offset,this.offset+e);return this.offset+=e,t}u8ArrayCopy(e){let t=this.#e.slice(this.offset,this.offset+e);return this.offset+=e,t}};var pr=Object.freeze([137,77,67,65,80,48,13,10]),bn;(function(n){n[n.MIN=1]="MIN",n[n.HEADER=1]="HEADER",n[n.FOOTER=2]="FOOTER",n[n.SCHEMA=3]="SCHEMA",n[n.CHANNEL=4]="CHANNEL",n[n.MESSAGE=5]="MESSAGE",n[n.CHUNK=6]="CHUNK",n[n.MESSAGE_INDEX=7]="MESSAGE_INDEX",n[n.CHUNK_INDEX=8]="CHUNK_INDEX",n[n.ATTACHMENT=9]="ATTACHMENT",n[n.ATTACHMENT_INDEX=10]="ATTACHMENT_INDEX",n[n.STATISTICS=11]="STATISTICS",n[n.METADATA=12]="METADATA",n[n.METADATA_INDEX=13]="METADATA_INDEX",n[n.SUMMARY_OFFSET=14]="SUMMARY_OFFSET",n[n.DATA_END=15]="DATA_END",n[n.MAX=15]="MAX"})(bn||(bn={}));function jc(n){if(n.bytesRemaining()<pr.length)return;let e=n.u8ArrayBorrow(pr.length);if(!pr.every((t,i)=>t===e[i]))throw new Error(`Expected MCAP magic '${pr.map(t=>t.toString(16).padStart(2,"0")).join(" ")}', found '${Array.from(e,(t,i)=>e[i].toString(16).padStart(2,"0")).join(" ")}'`);return{specVersion:"0"}}function Ja(n,e=!1){if(n.bytesRemaining()<9)return;let i=n.offset,r=n.uint8(),s=n.uint64();if(s>Number.MAX_SAFE_INTEGER)throw new Error(`Record content length ${s} is too large`);let o=Number(s);if(n.bytesRemaining()<o){n.offset=i;return}let a;switch(r){case bn.HEADER:a=RA(n,o);break;case bn.FOOTER:a=IA(n,o);break;case bn.SCHEMA:a=CA(n,o);break;case bn.CHANNEL:a=NA(n,o);break;case bn.MESSAGE:a=PA(n,o);break;case bn.CHUNK:a=LA(n,o);break;case bn.MESSAGE_INDEX:a=DA(n,o);break;case bn.CHUNK_INDEX:a=UA(n,o);break;case bn.ATTACHMENT:a=OA(n,o,e);break;case bn.ATTACHMENT_INDEX:a=FA(n,o);break;case bn.STATISTICS:a=BA(n,o);break;case bn.METADATA:a=kA(n,o);break;case bn.METADATA_INDEX:a=VA(n,o);break;case bn.SUMMARY_OFFSET:a=GA(n,o);break;case bn.DATA_END:a=zA(n,o);break;default:a=TA(n,o,r);break}return n.offset=i+9+o,a}function TA(n,e,t){let i=n.u8ArrayBorrow(e);return{type:"Unknown",opcode:t,data:i}}function RA(n,e){let t=n.offset,i=n.string(),r=n.string();return n.offset=t+e,{type:"Header",profile:i,library:r}}function IA(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint32();return n.offset=t+e,{type:"Footer",summaryStart:i,summaryOffsetStart:r,summaryCrc:s}}function CA(n,e){let t=n.offset,i=n.uint16(),r=n.string(),s=n.string(),o=n.uint32(),a=n.offset;if(e-(a-t)<o)throw new Error(`Schema data length ${o} exceeds bounds of record`);let l=n.u8ArrayCopy(o);return n.offset=t+e,{type:"Schema",id:i,encoding:s,name:r,data:l}}function NA(n,e){let t=n.offset,i=n.uint16(),r=n.uint16(),s=n.string(),o=n.string(),a=n.map(l=>l.string(),l=>l.string());return n.offset=t+e,{type:"Channel",id:i,schemaId:r,topic:s,messageEncoding:o,metadata:a}}function PA(n,e){let i=n.uint16(),r=n.uint32(),s=n.uint64(),o=n.uint64(),a=n.u8ArrayCopy(e-22);return{type:"Message",channelId:i,sequence:r,logTime:s,publishTime:o,data:a}}function LA(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint64(),o=n.uint32(),a=n.string(),l=Number(n.uint64()),u=n.offset-t;if(l+u>e)throw new Error("Chunk records length exceeds remaining record size");let h=n.u8ArrayCopy(l);return n.offset=t+e,{type:"Chunk",messageStartTime:i,messageEndTime:r,compression:a,uncompressedSize:s,uncompressedCrc:o,records:h}}function DA(n,e){let t=n.offset,i=n.uint16(),r=n.keyValuePairs(s=>s.uint64(),s=>s.uint64());return n.offset=t+e,{type:"MessageIndex",channelId:i,records:r}}function UA(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint64(),o=n.uint64(),a=n.map(f=>f.uint16(),f=>f.uint64()),l=n.uint64(),c=n.string(),u=n.uint64(),h=n.uint64();return n.offset=t+e,{type:"ChunkIndex",messageStartTime:i,messageEndTime:r,chunkStartOffset:s,chunkLength:o,messageIndexOffsets:a,messageIndexLength:l,compression:c,compressedSize:u,uncompressedSize:h}}function OA(n,e,t){let i=n.offset,r=n.uint64(),s=n.uint64(),o=n.string(),a=n.string(),l=n.uint64();if(BigInt(n.offset)+l>Number.MAX_SAFE_INTEGER)throw new Error(`Attachment too large: ${l}`);if(n.offset+Number(l)+4>i+e)throw new Error(`Attachment data length ${l} exceeds bounds of record`);let c=n.u8ArrayCopy(Number(l)),u=n.offset-i,h=n.uint32();if(t&&h!==0){n.offset=i;let f=n.u8ArrayBorrow(u),d=Fs(f);if(n.offset=i+u+4,d!==h)throw new Error(`Attachment CRC32 mismatch: expected ${h}, actual ${d}`)}return n.offset=i+e,{type:"Attachment",logTime:r,createTime:s,name:o,mediaType:a,data:c}}function FA(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.uint64(),o=n.uint64(),a=n.uint64(),l=n.string(),c=n.string();return n.offset=t+e,{type:"AttachmentIndex",offset:i,length:r,logTime:s,createTime:o,dataSize:a,name:l,mediaType:c}}function BA(n,e){let t=n.offset,i=n.uint64(),r=n.uint16(),s=n.uint32(),o=n.uint32(),a=n.uint32(),l=n.uint32(),c=n.uint64(),u=n.uint64(),h=n.map(f=>f.uint16(),f=>f.uint64());return n.offset=t+e,{type:"Statistics",messageCount:i,schemaCount:r,channelCount:s,attachmentCount:o,metadataCount:a,chunkCount:l,messageStartTime:c,messageEndTime:u,channelMessageCounts:h}}function kA(n,e){let t=n.offset,i=n.string(),r=n.map(s=>s.string(),s=>s.string());return n.offset=t+e,{type:"Metadata",metadata:r,name:i}}function VA(n,e){let t=n.offset,i=n.uint64(),r=n.uint64(),s=n.string();return n.offset=t+e,{type:"MetadataIndex",offset:i,length:r,name:s}}function GA(n,e){let t=n.offset,i=n.uint8(),r=n.uint64(),s=n.uint64();return n.offset=t+e,{type:"SummaryOffset",groupOpcode:i,groupStart:r,groupLength:s}}function zA(n,e){let t=n.offset,i=n.uint32();return n.offset=t+e,{type:"DataEnd",dataSectionCrc:i}}var No=class{#t=new ArrayBuffer(pr.length*2);#e=new DataView(this.#t,0,0);#n=new rs(this.#e);#o;#a;#i;#l;#r=!1;#c=this.#h();#s=new Map;constructor({includeChunks:e=!1,decompressHandlers:t={},validateCrcs:i=!0,noMagicPrefix:r=!1}={}){this.#a=e,this.#o=t,this.#i=i,this.#l=r}done(){return this.#r}bytesRemaining(){return this.#n.bytesRemaining()}append(e){if(this.#r)throw new Error("Already done reading");this.#u(e)}#u(e){let t=this.#n.offset,i=this.#e.byteLength-t,r=i+e.byteLength;if(r<=this.#t.byteLength)if(this.#e.byteOffset+this.#e.byteLength+e.byteLength<=this.#t.byteLength)new Uint8Array(this.#t,this.#e.byteOffset).set(e,this.#e.byteLength),this.#e=new DataView(this.#t,this.#e.byteOffset,this.#e.byteLength+e.byteLength),this.#n.reset(this.#e,this.#n.offset);else{let s=new Uint8Array(this.#t,this.#e.byteOffset+t,i),o=new Uint8Array(this.#t);o.set(s,0),o.set(e,s.byteLength),this.#e=new DataView(this.#t,0,s.byteLength+e.byteLength),this.#n.reset(this.#e)}else{this.#t=new ArrayBuffer(r*2);let s=new Uint8Array(this.#t),o=new Uint8Array(this.#e.buffer,this.#e.byteOffset+t,i);s.set(o,0),s.set(e,o.byteLength),this.#e=new DataView(this.#t,0,o.byteLength+e.byteLength),this.#n.reset(this.#e)}}nextRecord(){if(this.#r)return;let e=this.#c.next();if(e.value?.type==="Channel"){let t=this.#s.get(e.value.id);if(this.#s.set(e.value.id,e.value),t&&!HA(t,e.value))throw new Error(`Channel record for id ${e.value.id} (topic: ${e.value.topic}) differs from previous channel record of the same id.`)}else if(e.value?.type==="Message"){let t=e.value.channelId;if(!this.#s.get(t))throw new Error(`Encountered message on channel ${t} without prior channel record`)}return e.done===!0&&(this.#r=!0),e.value}*#h(){if(!this.#l){let i;for(;i=jc(this.#n),!i;)yield}let e;function t(i){return new Error(`${i} ${e?`[library=${e.library}]`:"[no header]"}`)}for(;;){let i;for(;i=Ja(this.#n,this.#i),!i;)yield;switch(i.type){case"Header":if(e)throw new Error(`Duplicate Header record: library=${e.library} profile=${e.profile} vs. library=${i.library} profile=${i.profile}`);e=i,yield i;break;case"Unknown":case"Schema":case"Channel":case"Message":case"MessageIndex":case"ChunkIndex":case"Attachment":case"AttachmentIndex":case"Statistics":case"Metadata":case"MetadataIndex":case"SummaryOffset":case"DataEnd":yield i;break;case"Chunk":{this.#a&&(yield i);let r=i.records;if(i.compression!==""&&r.byteLength>0){let l=this.#o[i.compression];if(!l)throw t(`Unsupported compression ${i.compression}`);r=l(r,i.uncompressedSize)}if(this.#i&&i.uncompressedCrc!==0){let l=Fs(r);if(l!==i.uncompressedCrc)throw t(`Incorrect chunk CRC ${l} (expected ${i.uncompressedCrc})`)}let s=new DataView(r.buffer,r.byteOffset,r.byteLength),o=new rs(s),a;for(;a=Ja(o,this.#i);)switch(a.type){case"Header":case"Footer":case"Chunk":case"MessageIndex":case"ChunkIndex":case"Attachment":case"AttachmentIndex":case"Statistics":case"Metadata":case"MetadataIndex":case"SummaryOffset":case"DataEnd":throw t(`${a.type} record not allowed inside a chunk`);case"Unknown":case"Schema":case"Channel":case"Message":yield a;break}if(o.bytesRemaining()!==0)throw t(`${o.bytesRemaining()} bytes remaining in chunk`);break}case"Footer":try{let r;for(;r=jc(this.#n),!r;)yield}catch(r){throw t(r.message)}if(this.#n.bytesRemaining()!==0)throw t(`${this.#n.bytesRemaining()} bytes remaining after MCAP footer and trailing magic`);return i}}}};function HA(n,e){if(!(n.id===e.id&&n.messageEncoding===e.messageEncoding&&n.schemaId===e.schemaId&&n.topic===e.topic&&n.metadata.size===e.metadata.size))return!1;for(let[t,i]of n.metadata.entries()){let r=e.metadata.get(t);if(i!==r)return!1}return!0}var WA="2.2.2",XA=`mcap-typescript/${WA}`;var KA=ArrayBuffer,un=Uint8Array,Qc=Uint16Array,$A=Int16Array;var eu=Int32Array,fp=function(n,e,t){if(un.prototype.slice)return un.prototype.slice.call(n,e,t);(e==null||e<0)&&(e=0),(t==null||t>n.length)&&(t=n.length);var i=new un(t-e);return i.set(n.subarray(e,t)),i},Qa=function(n,e,t,i){if(un.prototype.fill)return un.prototype.fill.call(n,e,t,i);for((t==null||t<0)&&(t=0),(i==null||i>n.length)&&(i=n.length);t<i;++t)n[t]=e;return n},qA=function(n,e,t,i){if(un.prototype.copyWithin)return un.prototype.copyWithin.call(n,e,t,i);for((t==null||t<0)&&(t=0),(i==null||i>n.length)&&(i=n.length);t<i;)n[e++]=n[t++]};var JA=["invalid zstd data","window size too large (>2046MB)","invalid block type","FSE accuracy too high","match distance too far back","unexpected EOF"],Sn=function(n,e,t){var i=new Error(e||JA[n]);if(i.code=n,Error.captureStackTrace&&Error.captureStackTrace(i,Sn),!t)throw i;return i},Nx=function(n,e,t){for(var i=0,r=0;i<t;++i)r|=n[e++]<<(i<<3);return r},jA=function(n,e){return(n[e]|n[e+1]<<8|n[e+2]<<16|n[e+3]<<24)>>>0},QA=function(n,e){var t=n[0]|n[1]<<8|n[2]<<16;if(t==3126568&&n[3]==253){var i=n[4],r=i>>5&1,s=i>>2&1,o=i&3,a=i>>6;i&8&&Sn(0);var l=6-r,c=o==3?4:o,u=Nx(n,l,c);l+=c;var h=a?1<<a:r,f=Nx(n,l,h)+(a==1&&256),d=f;if(!r){var p=1<<10+(n[5]>>3);d=p+(p>>3)*(n[5]&7)}d>2145386496&&Sn(1);var x=new un((e==1?f||d:e?0:d)+12);return x[0]=1,x[4]=4,x[8]=8,{b:l+h,y:0,l:0,d:u,w:e&&e!=1?e:x.subarray(12),e:d,o:new eu(x.buffer,0,3),u:f,c:s,m:Math.min(131072,d)}}else if((t>>4|n[3]<<20)==25481893)return jA(n,4)+8;Sn(0)},Bs=function(n){for(var e=0;1<<e<=n;++e);return e-1},el=function(n,e,t){var i=(e<<3)+4,r=(n[e]&15)+5;r>t&&Sn(3);for(var s=1<<r,o=s,a=-1,l=-1,c=-1,u=s,h=new KA(512+(s<<2)),f=new $A(h,0,256),d=new Qc(h,0,256),p=new Qc(h,512,s),x=512+(s<<1),m=new un(h,x,s),g=new un(h,x+s);a<255&&o>0;){var v=Bs(o+1),T=i>>3,M=(1<<v+1)-1,R=(n[T]|n[T+1]<<8|n[T+2]<<16)>>(i&7)&M,w=(1<<v)-1,y=M-o-1,A=R&w;if(A<y?(i+=v,R=A):(i+=v+1,R>w&&(R-=y)),f[++a]=--R,R==-1?(o+=R,m[--u]=a):o-=R,!R)do{var k=i>>3;l=(n[k]|n[k+1]<<8)>>(i&7)&3,i+=2,a+=l}while(l==3)}(a>255||o)&&Sn(0);for(var D=0,L=(s>>1)+(s>>3)+3,H=s-1,z=0;z<=a;++z){var N=f[z];if(N<1){d[z]=-N;continue}for(c=0;c<N;++c){m[D]=z;do D=D+L&H;while(D>=u)}}for(D&&Sn(0),c=0;c<s;++c){var F=d[m[c]]++,Z=g[c]=r-Bs(F);p[c]=(F<<Z)-s}return[i+7>>3,{b:r,s:m,n:g,t:p}]},e1=function(n,e){var t=0,i=-1,r=new un(292),s=n[e],o=r.subarray(0,256),a=r.subarray(256,268),l=new Qc(r.buffer,268);if(s<128){var c=el(n,e+1,6),u=c[0],h=c[1];e+=s;var f=u<<3,d=n[e];d||Sn(0);for(var p=0,x=0,m=h.b,g=m,v=(++e<<3)-8+Bs(d);v-=m,!(v<f);){var T=v>>3;if(p+=(n[T]|n[T+1]<<8)>>(v&7)&(1<<m)-1,o[++i]=h.s[p],v-=g,v<f)break;T=v>>3,x+=(n[T]|n[T+1]<<8)>>(v&7)&(1<<g)-1,o[++i]=h.s[x],m=h.n[p],p=h.t[p],g=h.n[x],x=h.t[x]}++i>255&&Sn(0)}else{for(i=s-127;t<i;t+=2){var M=n[++e];o[t]=M>>4,o[t+1]=M&15}++e}var R=0;for(t=0;t<i;++t){var w=o[t];w>11&&Sn(0),R+=w&&1<<w-1}var y=Bs(R)+1,A=1<<y,k=A-R;for(k&k-1&&Sn(0),o[i++]=Bs(k)+1,t=0;t<i;++t){var w=o[t];++a[o[t]=w&&y+1-w]}var D=new un(A<<1),L=D.subarray(0,A),H=D.subarray(A);for(l[y]=0,t=y;t>0;--t){var z=l[t];Qa(H,t,z,l[t-1]=z+a[t]*(1<<y-t))}for(l[0]!=A&&Sn(0),t=0;t<i;++t){var N=o[t];if(N){var F=l[N];Qa(L,t,F,l[N]=F+(1<<y-N))}}return[e,{n:H,b:y,s:L}]},t1=el(new un([81,16,99,140,49,198,24,99,12,33,196,24,99,102,102,134,70,146,4]),0,6)[1],n1=el(new un([33,20,196,24,99,140,33,132,16,66,8,33,132,16,66,8,33,68,68,68,68,68,68,68,68,36,9]),0,6)[1],i1=el(new un([32,132,16,66,102,70,68,68,68,68,36,73,2]),0,5)[1],Px=function(n,e){for(var t=n.length,i=new eu(t),r=0;r<t;++r)i[r]=e,e+=1<<n[r];return i},dp=new un(new eu([0,0,0,0,16843009,50528770,134678020,202050057,269422093]).buffer,0,36),r1=Px(dp,0),pp=new un(new eu([0,0,0,0,0,0,0,0,16843009,50528770,117769220,185207048,252579084,16]).buffer,0,53),s1=Px(pp,3),ja=function(n,e,t){var i=n.length,r=e.length,s=n[i-1],o=(1<<t.b)-1,a=-t.b;s||Sn(0);for(var l=0,c=t.b,u=(i<<3)-8+Bs(s)-c,h=-1;u>a&&h<r;){var f=u>>3,d=(n[f]|n[f+1]<<8|n[f+2]<<16)>>(u&7);l=(l<<c|d)&o,e[++h]=t.s[l],u-=c=t.n[l]}(u!=a||h+1!=r)&&Sn(0)},o1=function(n,e,t){var i=6,r=e.length,s=r+3>>2,o=s<<1,a=s+o;ja(n.subarray(i,i+=n[0]|n[1]<<8),e.subarray(0,s),t),ja(n.subarray(i,i+=n[2]|n[3]<<8),e.subarray(s,o),t),ja(n.subarray(i,i+=n[4]|n[5]<<8),e.subarray(o,a),t),ja(n.subarray(i),e.subarray(a),t)},a1=function(n,e,t){var i,r=e.b,s=n[r],o=s>>1&3;e.l=s&1;var a=s>>3|n[r+1]<<5|n[r+2]<<13,l=(r+=3)+a;if(o==1)return r>=n.length?void 0:(e.b=r+1,t?(Qa(t,n[r],e.y,e.y+=a),t):Qa(new un(a),n[r]));if(!(l>n.length)){if(o==0)return e.b=l,t?(t.set(n.subarray(r,l),e.y),e.y+=a,t):fp(n,r,l);if(o==2){var c=n[r],u=c&3,h=c>>2&3,f=c>>4,d=0,p=0;u<2?h&1?f|=n[++r]<<4|(h&2&&n[++r]<<12):f=c>>3:(p=h,h<2?(f|=(n[++r]&63)<<4,d=n[r]>>6|n[++r]<<2):h==2?(f|=n[++r]<<4|(n[++r]&3)<<12,d=n[r]>>2|n[++r]<<6):(f|=n[++r]<<4|(n[++r]&63)<<12,d=n[r]>>6|n[++r]<<2|n[++r]<<10)),++r;var x=t?t.subarray(e.y,e.y+e.m):new un(e.m),m=x.length-f;if(u==0)x.set(n.subarray(r,r+=f),m);else if(u==1)Qa(x,n[r++],m);else{var g=e.h;if(u==2){var v=e1(n,r);d+=r-(r=v[0]),e.h=g=v[1]}else g||Sn(0);(p?o1:ja)(n.subarray(r,r+=d),x.subarray(m),g)}var T=n[r++];if(T){T==255?T=(n[r++]|n[r++]<<8)+32512:T>127&&(T=T-128<<8|n[r++]);var M=n[r++];M&3&&Sn(0);for(var R=[n1,i1,t1],w=2;w>-1;--w){var y=M>>(w<<1)+2&3;if(y==1){var A=new un([0,0,n[r++]]);R[w]={s:A.subarray(2,3),n:A.subarray(0,1),t:new Qc(A.buffer,0,1),b:0}}else y==2?(i=el(n,r,9-(w&1)),r=i[0],R[w]=i[1]):y==3&&(e.t||Sn(0),R[w]=e.t[w])}var k=e.t=R,D=k[0],L=k[1],H=k[2],z=n[l-1];z||Sn(0);var N=(l<<3)-8+Bs(z)-H.b,F=N>>3,Z=0,V=(n[F]|n[F+1]<<8)>>(N&7)&(1<<H.b)-1;F=(N-=L.b)>>3;var le=(n[F]|n[F+1]<<8)>>(N&7)&(1<<L.b)-1;F=(N-=D.b)>>3;var q=(n[F]|n[F+1]<<8)>>(N&7)&(1<<D.b)-1;for(++T;--T;){var Q=H.s[V],ie=H.n[V],fe=D.s[q],he=D.n[q],ee=L.s[le],ge=L.n[le];F=(N-=ee)>>3;var ye=1<<ee,xe=ye+((n[F]|n[F+1]<<8|n[F+2]<<16|n[F+3]<<24)>>>(N&7)&ye-1);F=(N-=pp[fe])>>3;var _e=s1[fe]+((n[F]|n[F+1]<<8|n[F+2]<<16)>>(N&7)&(1<<pp[fe])-1);F=(N-=dp[Q])>>3;var ze=r1[Q]+((n[F]|n[F+1]<<8|n[F+2]<<16)>>(N&7)&(1<<dp[Q])-1);if(F=(N-=ie)>>3,V=H.t[V]+((n[F]|n[F+1]<<8)>>(N&7)&(1<<ie)-1),F=(N-=he)>>3,q=D.t[q]+((n[F]|n[F+1]<<8)>>(N&7)&(1<<he)-1),F=(N-=ge)>>3,le=L.t[le]+((n[F]|n[F+1]<<8)>>(N&7)&(1<<ge)-1),xe>3)e.o[2]=e.o[1],e.o[1]=e.o[0],e.o[0]=xe-=3;else{var $e=xe-(ze!=0);$e?(xe=$e==3?e.o[0]-1:e.o[$e],$e>1&&(e.o[2]=e.o[1]),e.o[1]=e.o[0],e.o[0]=xe):xe=e.o[0]}for(var w=0;w<ze;++w)x[Z+w]=x[m+w];Z+=ze,m+=ze;var Fe=Z-xe;if(Fe<0){var st=-Fe,ct=e.e+Fe;st>_e&&(st=_e);for(var w=0;w<st;++w)x[Z+w]=e.w[ct+w];Z+=st,_e-=st,Fe=0}for(var w=0;w<_e;++w)x[Z+w]=x[Fe+w];Z+=_e}if(Z!=m)for(;m<x.length;)x[Z++]=x[m++];else Z=x.length;t?e.y+=Z:x=fp(x,0,Z)}else if(t){if(e.y+=f,m)for(var w=0;w<f;++w)x[w]=x[m+w]}else m&&(x=fp(x,m));return e.b=l,x}Sn(2)}},l1=function(n,e){if(n.length==1)return n[0];for(var t=new un(e),i=0,r=0;i<n.length;++i){var s=n[i];t.set(s,r),r+=s.length}return t};function Lx(n,e){for(var t=[],i=+!e,r=0,s=0;n.length;){var o=QA(n,i||e);if(typeof o=="object"){for(i?(e=null,o.w.length==o.u&&(t.push(e=o.w),s+=o.u)):(t.push(e),o.e=0);!o.l;){var a=a1(n,o,e);a||Sn(5),e?o.e=o.y:(t.push(a),s+=a.length,qA(o.w,0,a.length),o.w.set(a,o.w.length-a.length))}r=o.b+o.c*4}else r=o;n=n.subarray(r)}return l1(t,s)}var Jx=IS(Zx(),1);function au(n){return{positionsM:Float32Array.from(n.nodeXyzM),triangles:Uint32Array.from(n.triangles)}}var ss=n=>[n?.x??0,n?.y??0,n?.z??0];function v1(n){switch(n){case 1:return"stuck";case 2:return"slipping";case 3:return"tip";default:return"other"}}function Kx(n){let e=n.d3;return e?{displacementM:n.surfaceDisplacementM.length?Float32Array.from(n.surfaceDisplacementM):null,needleM:e.needleShapeM.map(ss),points:e.contacts.map(t=>({posM:ss(t.positionM),state:v1(t.state)})),targets:e.targets.map(t=>({centreM:ss(t.centerM),radiusM:t.radiusM,hit:t.hit}))}:null}function $x(n){let e=n.base;if(!e?.positionM||!e.orientation)return null;let t=e.orientation;return{positionM:ss(e.positionM),quaternion:[t.w,t.x,t.y,t.z]}}function qx(n,e){let[t,i,r]=ss(e.forceN),[s,o,a]=ss(e.torqueNm),l=b1(e),c=t*l[0]+i*l[1]+r*l[2],u=Math.hypot(t-c*l[0],i-c*l[1],r-c*l[2]);return{timeS:n.timeS,depthMm:n.insertedLengthM*1e3,axialN:e.axialForceN,lateralN:u,torqueMnm:Math.hypot(s,o,a)*1e3}}function b1(n){let e=n.needleShapeM;if(e.length<2)return[1,0,0];let[t,i]=[ss(e[0]),ss(e[1])],r=Math.hypot(i[0]-t[0],i[1]-t[1],i[2]-t[2])||1;return[(i[0]-t[0])/r,(i[1]-t[1])/r,(i[2]-t[2])/r]}function lu(n){me.frame=n,Gy(me,n);let e=et("depth");e.textContent=`${(n.insertedLengthM*1e3).toFixed(2)} mm`,e.dataset.depthM=String(n.insertedLengthM),an("depthM",n.insertedLengthM),et("axial").textContent=`${n.forceAxialN.toFixed(3)} N`,et("lateral").textContent=`${n.forceLateralN.toFixed(3)} N`,et("torque").textContent=`${(n.torqueNm*1e3).toFixed(2)} mN·m`;let t=0,i=0,r=0,s=n.d3;if(s){let[l,c,u]=[s.forceN?.x??0,s.forceN?.y??0,s.forceN?.z??0];et("axial").textContent=`${s.axialForceN.toFixed(3)} N`,et("lateral").textContent=`(${l.toFixed(3)}, ${c.toFixed(3)}, ${u.toFixed(3)}) N`;let h=s.torqueNm;et("torque").textContent=`(${[h?.x??0,h?.y??0,h?.z??0].map(f=>(f*1e3).toFixed(2)).join(", ")}) mN·m`}let o=s?s.contacts.map(l=>l.state):n.needleNodes.map(l=>l.state);for(let l of o)l===1?t++:l===2?i++:l===3&&r++;et("nodes").textContent=`${t}/${i}/${r}`;let a=s?s.targets:n.targets;et("targets").textContent=a.length?a.map(l=>`${l.name}: ${l.hit?"hit":"missed"}`).join(", "):"none",et("bevel").textContent=n.bevelSide===0?"symmetric":n.bevelSide>0?"+n side":"−n side",an("bevelSide",n.bevelSide),an("fault",n.faulted?n.fault:""),n.faulted&&(et("status").textContent=`session faulted: ${n.fault}`),me.dirty=!0}function Mp(n){an("frames",n),et("frames").textContent=String(n)}var S1=5e3,Ep=()=>et("rec-select",HTMLSelectElement),cu=()=>et("slider",HTMLInputElement);async function uu(){try{let n=await Ba.listRecordings({},me.session?hi(me.session.token):{});Ep().replaceChildren(...n.recordings.map(e=>{let t=document.createElement("option");return t.value=e.name,t.textContent=`${e.name} (${e.messages} frames${e.finished?"":", recording"})`,t}))}catch(n){zt(`ListRecordings: ${String(n)}`)}}async function wp(n){let e=me.session;if(!e)return zt("watch a session first");try{let t={sessionId:e.id},i=n?await Ba.startRecording({...t,includeDisplacements:!0},hi(e.token)):await Ba.stopRecording(t,hi(e.token));zt(`${n?"recording to":"recorded"} ${i.name}`),await uu(),Ep().value=i.name}catch(t){zt(`${n?"StartRecording":"StopRecording"}: ${String(t)}`)}}function M1(n){let e=new No({decompressHandlers:{zstd:(s,o)=>Lx(s,new Uint8Array(Number(o))),lz4:(s,o)=>Uint8Array.from((0,Jx.decompress)(s,Number(o)))}});e.append(n);let t=new Map,i=new Map,r={frames:[],mesh:null,surface:null};for(let s=e.nextRecord();s;s=e.nextRecord())if(s.type==="Schema")i.set(s.id,s.name);else if(s.type==="Channel")t.set(s.id,i.get(s.schemaId)??"");else if(s.type==="Message"){let o=t.get(s.channelId);o==="needlesim.v1.Frame"?r.frames.push(ii(Ry,s.data)):o==="needlesim.v1.Mesh"?r.mesh=ii(Ay,s.data):o==="needlesim.v1.Surface"&&(r.surface=ii(Ty,s.data))}return r}function E1(n){let e=[],t=[],i=0;for(let r of n)(r.nodeDisplacementM.length||r.surfaceDisplacementM.length)&&i++,r.nodeDisplacementM.length?e=r.nodeDisplacementM:e.length&&(r.nodeDisplacementM=e),r.surfaceDisplacementM.length?t=r.surfaceDisplacementM:t.length&&(r.surfaceDisplacementM=t);return i}async function jx(){let n=Ep().value;if(!n)return zt("no recording selected");try{zt(`downloading ${n}…`);let e=[],t=0;for await(let p of Ba.downloadRecording({name:n},me.session?hi(me.session.token):{}))e.push(p.data),t+=p.data.length;let i=new Uint8Array(t),r=0;for(let p of e)i.set(p,r),r+=p.length;let s=M1(i),o=s.frames;if(!o.length)return zt(`${n} holds no frames`);let a=E1(o),l=Math.max(1,Math.ceil(o.length/S1)),c=o.filter((p,x)=>x%l===0),u=n.replace(/-\d{8}T\d{6}Z.*$/,""),h=hr.get(u)??(me.session?.id===u?me.session.token:void 0);if(s.surface)me.surface3=au(s.surface),me.dim=3;else if(s.mesh)me.mesh=za(s.mesh),me.viewBounds=null,me.dim=2;else if(h&&me.session?.id!==u)try{me.mesh=za(await ts.getMesh({sessionId:u},hi(h))),me.viewBounds=null}catch{}let f=me.playback;f.frames=c,f.history=xo.of(c.map(vo)),me.mode="playback",an("state","playback"),an("playbackFrames",c.length),an("dim",me.dim),an("playbackFields",a);let d=cu();d.max=String(c.length-1),d.value="0",Ap(0),zt(`${n}: ${o.length} frames${l>1?`, every ${l}th shown`:""}`)}catch(e){zt(`DownloadRecording: ${String(e)}`)}}function Ap(n){let e=me.playback.frames[n];e&&(lu(e),et("rec-time").textContent=`${e.timeS.toFixed(3)} s`)}function Qx(){me.playback.playing=!1,et("play").textContent="▶",Ap(Number(cu().value))}function ev(){let n=me.playback;if(!(me.mode!=="playback"||!n.frames.length)&&(n.playing=!n.playing,et("play").textContent=n.playing?"❚❚":"▶",n.playing)){let e=cu();Number(e.value)>=n.frames.length-1&&(e.value="0"),n.startedMs=performance.now(),n.startedSimS=n.frames[Number(e.value)].timeS,requestAnimationFrame(nv)}}function tv(){me.playback.playing=!1}function nv(){let n=me.playback;if(!n.playing||me.mode!=="playback")return;let e=n.startedSimS+(performance.now()-n.startedMs)/1e3,t=cu(),i=Number(t.value);for(;i<n.frames.length-1&&n.frames[i+1].timeS<=e;)i++;if(t.value=String(i),Ap(i),i>=n.frames.length-1){n.playing=!1,et("play").textContent="▶";return}requestAnimationFrame(nv)}var Tp=()=>et("session-select",HTMLSelectElement),hu=()=>et("token",HTMLInputElement);async function fu(n){let e=Tp();try{let t=await ts.listSessions({}),i=n??e.value;e.replaceChildren(...t.sessions.map(s=>{let o=document.createElement("option");return o.value=s.sessionId,o.textContent=`${s.sessionId} (${s.sceneName}, ${s.nNodes} nodes${hr.has(s.sessionId)?", token known":""})`,o})),i&&t.sessions.some(s=>s.sessionId===i)&&(e.value=i);let r=hr.get(e.value);r&&(hu().value=r)}catch(t){zt(`ListSessions: ${String(t)}`)}}async function iv(){let n=et("example-select",HTMLSelectElement).value;try{zt(`creating a session of ${n}…`);let e=await ts.createSession({scene:{source:{case:"example",value:n}}}),t=e.session?.sessionId??"";hr.set(t,e.controllerToken),await fu(t),hu().value=e.controllerToken,zt(""),await il(t,e.controllerToken)}catch(e){zt(`CreateSession: ${String(e)}`)}}function rv(){let n=Tp().value,e=hu().value.trim();if(!n)return zt("no session selected");if(!e)return zt("paste the session's controller or observer token (printed in the server log)");il(n,e)}function sv(){hu().value=hr.get(Tp().value)??""}async function il(n,e){me.streamAbort?.abort(),By(n,e),hr.set(n,e),Mp(0),an("session",n);let t=new URL(window.location.href);t.searchParams.set("session",n),t.searchParams.set("token",e),window.history.replaceState(null,"",t);try{(await ts.getSession({sessionId:n},hi(e))).dimension===3?(me.surface3=au(await ts.getSurface({sessionId:n},hi(e))),me.dim=3):me.mesh=za(await ts.getMesh({sessionId:n},hi(e))),an("dim",me.dim)}catch(r){zt(`opening the session: ${String(r)}`);return}let i=new AbortController;me.streamAbort=i,an("state","live"),zt("");try{let r=Ly.observe({sessionId:n,rateHz:60,includeDisplacements:!0},{...hi(e),signal:i.signal});for await(let s of r)Mp(++me.framesReceived),me.history.push(s.d3?qx(s,s.d3):vo(s)),me.mode==="live"&&lu(s);i.signal.aborted||zt("the session's frame stream ended")}catch(r){i.signal.aborted||zt(`Observe: ${String(r)}`)}}var _s={LEFT:0,MIDDLE:1,RIGHT:2,ROTATE:0,DOLLY:1,PAN:2},xs={ROTATE:0,PAN:1,DOLLY_PAN:2,DOLLY_ROTATE:3},Dv=0,im=1,Uv=2;var Dl=1,Ov=2,aa=3,vs=0,ui=1,Fi=2,Ys=0,la=1,rm=2,sm=3,om=4,Fv=5;var Zs=100,Bv=101,kv=102,Vv=103,Gv=104,zv=200,Hv=201,Wv=202,Xv=203,am=204,lm=205,Yv=206,Zv=207,Kv=208,$v=209,qv=210,Jv=211,jv=212,Qv=213,eb=214,ku=0,Vu=1,Gu=2,Ko=3,zu=4,Hu=5,Wu=6,Xu=7,_h=0,tb=1,nb=2,br=0,cm=1,um=2,hm=3,fm=4,dm=5,pm=6,mm=7;var gm=300,Ks=301,ca=302,xh=303,vh=304,Yu=1e3,yr=1001,Zu=1002,kn=1003,ib=1004;var Ul=1005;var li=1006,bh=1007;var Xr=1008;var di=1009,ym=1010,_m=1011,ua=1012,Sh=1013,Qi=1014,er=1015,tr=1016,Mh=1017,Eh=1018,$s=1020,xm=35902,vm=35899,bm=1021,Sm=1022,nr=1023,zr=1026,Yr=1027,Mm=1028,wh=1029,bs=1030,Ah=1031;var Th=1033,Ol=33776,Fl=33777,Bl=33778,kl=33779,Rh=35840,Ih=35841,Ch=35842,Nh=35843,Ph=36196,Lh=37492,Dh=37496,Uh=37488,Oh=37489,Vl=37490,Fh=37491,Bh=37808,kh=37809,Vh=37810,Gh=37811,zh=37812,Hh=37813,Wh=37814,Xh=37815,Yh=37816,Zh=37817,Kh=37818,$h=37819,qh=37820,Jh=37821,jh=36492,Qh=36494,ef=36495,tf=36283,nf=36284,Gl=36285,rf=36286;var fl=2300,Ku=2301,Fu=2302,$p=2303,qp=2400,Jp=2401,jp=2402;var rb=3200;var sf=0,sb=1,Zr="",wi="srgb",dl="srgb-linear",pl="linear",Nt="srgb";var Bu=7680;var ob=519,ab=512,lb=513,cb=514,Em=515,ub=516,hb=517,wm=518,Am=519,fb=35044;var Tm="300 es",Oi=2e3,$o=2001;function w1(n){for(let e=n.length-1;e>=0;--e)if(n[e]>=65535)return!0;return!1}function A1(n){return ArrayBuffer.isView(n)&&!(n instanceof DataView)}function ml(n){return document.createElementNS("http://www.w3.org/1999/xhtml",n)}function db(){let n=ml("canvas");return n.style.display="block",n}var ov={},qo=null;function Rm(...n){let e="THREE."+n.shift();qo?qo("log",e,...n):console.log(e,...n)}function pb(n){let e=n[0];if(typeof e=="string"&&e.startsWith("TSL:")){let t=n[1];t&&t.isStackTrace?n[0]+=" "+t.getLocation():n[1]='Stack trace not available. Enable "THREE.Node.captureStackTrace" to capture stack traces.'}return n}function Ke(...n){n=pb(n);let e="THREE."+n.shift();if(qo)qo("warn",e,...n);else{let t=n[0];t&&t.isStackTrace?console.warn(t.getError(e)):console.warn(e,...n)}}function nt(...n){n=pb(n);let e="THREE."+n.shift();if(qo)qo("error",e,...n);else{let t=n[0];t&&t.isStackTrace?console.error(t.getError(e)):console.error(e,...n)}}function cl(...n){let e=n.join(" ");e in ov||(ov[e]=!0,Ke(...n))}function mb(n,e,t){return new Promise(function(i,r){function s(){switch(n.clientWaitSync(e,n.SYNC_FLUSH_COMMANDS_BIT,0)){case n.WAIT_FAILED:r();break;case n.TIMEOUT_EXPIRED:setTimeout(s,t);break;default:i()}}setTimeout(s,t)})}var gb={[ku]:ku,[Gu]:Wu,[zu]:zu,[Ko]:Hu,[Vu]:Vu,[Wu]:Gu,[Xu]:Xu,[Hu]:Ko},ji=class{addEventListener(e,t){this._listeners===void 0&&(this._listeners={});let i=this._listeners;i[e]===void 0&&(i[e]=[]),i[e].indexOf(t)===-1&&i[e].push(t)}hasEventListener(e,t){let i=this._listeners;return i===void 0?!1:i[e]!==void 0&&i[e].indexOf(t)!==-1}removeEventListener(e,t){let i=this._listeners;if(i===void 0)return;let r=i[e];if(r!==void 0){let s=r.indexOf(t);s!==-1&&r.splice(s,1)}}dispatchEvent(e){let t=this._listeners;if(t===void 0)return;let i=t[e.type];if(i!==void 0){e.target=this;let r=i.slice(0);for(let s=0,o=r.length;s<o;s++)r[s].call(this,e);e.target=null}}},Zn=["00","01","02","03","04","05","06","07","08","09","0a","0b","0c","0d","0e","0f","10","11","12","13","14","15","16","17","18","19","1a","1b","1c","1d","1e","1f","20","21","22","23","24","25","26","27","28","29","2a","2b","2c","2d","2e","2f","30","31","32","33","34","35","36","37","38","39","3a","3b","3c","3d","3e","3f","40","41","42","43","44","45","46","47","48","49","4a","4b","4c","4d","4e","4f","50","51","52","53","54","55","56","57","58","59","5a","5b","5c","5d","5e","5f","60","61","62","63","64","65","66","67","68","69","6a","6b","6c","6d","6e","6f","70","71","72","73","74","75","76","77","78","79","7a","7b","7c","7d","7e","7f","80","81","82","83","84","85","86","87","88","89","8a","8b","8c","8d","8e","8f","90","91","92","93","94","95","96","97","98","99","9a","9b","9c","9d","9e","9f","a0","a1","a2","a3","a4","a5","a6","a7","a8","a9","aa","ab","ac","ad","ae","af","b0","b1","b2","b3","b4","b5","b6","b7","b8","b9","ba","bb","bc","bd","be","bf","c0","c1","c2","c3","c4","c5","c6","c7","c8","c9","ca","cb","cc","cd","ce","cf","d0","d1","d2","d3","d4","d5","d6","d7","d8","d9","da","db","dc","dd","de","df","e0","e1","e2","e3","e4","e5","e6","e7","e8","e9","ea","eb","ec","ed","ee","ef","f0","f1","f2","f3","f4","f5","f6","f7","f8","f9","fa","fb","fc","fd","fe","ff"],av=1234567,ul=Math.PI/180,Jo=180/Math.PI;function ha(){let n=Math.random()*4294967295|0,e=Math.random()*4294967295|0,t=Math.random()*4294967295|0,i=Math.random()*4294967295|0;return(Zn[n&255]+Zn[n>>8&255]+Zn[n>>16&255]+Zn[n>>24&255]+"-"+Zn[e&255]+Zn[e>>8&255]+"-"+Zn[e>>16&15|64]+Zn[e>>24&255]+"-"+Zn[t&63|128]+Zn[t>>8&255]+"-"+Zn[t>>16&255]+Zn[t>>24&255]+Zn[i&255]+Zn[i>>8&255]+Zn[i>>16&255]+Zn[i>>24&255]).toLowerCase()}function gt(n,e,t){return Math.max(e,Math.min(t,n))}function Im(n,e){return(n%e+e)%e}function T1(n,e,t,i,r){return i+(n-e)*(r-i)/(t-e)}function R1(n,e,t){return n!==e?(t-n)/(e-n):0}function hl(n,e,t){return(1-t)*n+t*e}function I1(n,e,t,i){return hl(n,e,1-Math.exp(-t*i))}function C1(n,e=1){return e-Math.abs(Im(n,e*2)-e)}function N1(n,e,t){return n<=e?0:n>=t?1:(n=(n-e)/(t-e),n*n*(3-2*n))}function P1(n,e,t){return n<=e?0:n>=t?1:(n=(n-e)/(t-e),n*n*n*(n*(n*6-15)+10))}function L1(n,e){return n+Math.floor(Math.random()*(e-n+1))}function D1(n,e){return n+Math.random()*(e-n)}function U1(n){return n*(.5-Math.random())}function O1(n){n!==void 0&&(av=n);let e=av+=1831565813;return e=Math.imul(e^e>>>15,e|1),e^=e+Math.imul(e^e>>>7,e|61),((e^e>>>14)>>>0)/4294967296}function F1(n){return n*ul}function B1(n){return n*Jo}function k1(n){return n>0&&Number.isInteger(n)&&2**Math.round(Math.log2(n))===n}function V1(n){return Math.pow(2,Math.ceil(Math.log(n)/Math.LN2))}function Cm(n){return Math.pow(2,Math.floor(Math.log(n)/Math.LN2))}function G1(n,e,t,i,r){let s=Math.cos,o=Math.sin,a=s(t/2),l=o(t/2),c=s((e+i)/2),u=o((e+i)/2),h=s((e-i)/2),f=o((e-i)/2),d=s((i-e)/2),p=o((i-e)/2);switch(r){case"XYX":n.set(a*u,l*h,l*f,a*c);break;case"YZY":n.set(l*f,a*u,l*h,a*c);break;case"ZXZ":n.set(l*h,l*f,a*u,a*c);break;case"XZX":n.set(a*u,l*p,l*d,a*c);break;case"YXY":n.set(l*d,a*u,l*p,a*c);break;case"ZYZ":n.set(l*p,l*d,a*u,a*c);break;default:Ke("MathUtils: .setQuaternionFromProperEuler() encountered an unknown order: "+r)}}function Nm(n){switch(n.constructor){case Uint32Array:return 4294967295;case Uint16Array:return 65535;case Uint8Array:case Uint8ClampedArray:return 255;case Int32Array:return 2147483647;case Int16Array:return 32767;case Int8Array:return 127;default:return}}function yb(n,e){if(e.constructor===Float32Array)return n;let t=Nm(e);if(t===void 0)throw new Error("THREE.MathUtils: Invalid component type.");return Math.max(n/t,-1)}function _b(n,e){if(e.constructor===Float32Array)return n;let t=Nm(e);if(t===void 0)throw new Error("THREE.MathUtils: Invalid component type.");return Math.round(n*t)}var Pm={DEG2RAD:ul,RAD2DEG:Jo,generateUUID:ha,clamp:gt,euclideanModulo:Im,mapLinear:T1,inverseLerp:R1,lerp:hl,damp:I1,pingpong:C1,smoothstep:N1,smootherstep:P1,randInt:L1,randFloat:D1,randFloatSpread:U1,seededRandom:O1,degToRad:F1,radToDeg:B1,isPowerOfTwo:k1,ceilPowerOfTwo:V1,floorPowerOfTwo:Cm,setQuaternionFromProperEuler:G1,normalize:_b,denormalize:yb},it=class{static{this.prototype.isVector2=!0}constructor(e=0,t=0){this.x=e,this.y=t}get width(){return this.x}set width(e){this.x=e}get height(){return this.y}set height(e){this.y=e}set(e,t){return this.x=e,this.y=t,this}setScalar(e){return this.x=e,this.y=e,this}setX(e){return this.x=e,this}setY(e){return this.y=e,this}setComponent(e,t){switch(e){case 0:this.x=t;break;case 1:this.y=t;break;default:throw new Error("THREE.Vector2: index is out of range: "+e)}return this}getComponent(e){switch(e){case 0:return this.x;case 1:return this.y;default:throw new Error("THREE.Vector2: index is out of range: "+e)}}clone(){return new this.constructor(this.x,this.y)}copy(e){return this.x=e.x,this.y=e.y,this}add(e){return this.x+=e.x,this.y+=e.y,this}addScalar(e){return this.x+=e,this.y+=e,this}addVectors(e,t){return this.x=e.x+t.x,this.y=e.y+t.y,this}addScaledVector(e,t){return this.x+=e.x*t,this.y+=e.y*t,this}sub(e){return this.x-=e.x,this.y-=e.y,this}subScalar(e){return this.x-=e,this.y-=e,this}subVectors(e,t){return this.x=e.x-t.x,this.y=e.y-t.y,this}multiply(e){return this.x*=e.x,this.y*=e.y,this}multiplyScalar(e){return this.x*=e,this.y*=e,this}divide(e){return this.x/=e.x,this.y/=e.y,this}divideScalar(e){return this.multiplyScalar(1/e)}applyMatrix3(e){let t=this.x,i=this.y,r=e.elements;return this.x=r[0]*t+r[3]*i+r[6],this.y=r[1]*t+r[4]*i+r[7],this}min(e){return this.x=Math.min(this.x,e.x),this.y=Math.min(this.y,e.y),this}max(e){return this.x=Math.max(this.x,e.x),this.y=Math.max(this.y,e.y),this}clamp(e,t){return this.x=gt(this.x,e.x,t.x),this.y=gt(this.y,e.y,t.y),this}clampScalar(e,t){return this.x=gt(this.x,e,t),this.y=gt(this.y,e,t),this}clampLength(e,t){let i=this.length();return this.divideScalar(i||1).multiplyScalar(gt(i,e,t))}floor(){return this.x=Math.floor(this.x),this.y=Math.floor(this.y),this}ceil(){return this.x=Math.ceil(this.x),this.y=Math.ceil(this.y),this}round(){return this.x=Math.round(this.x),this.y=Math.round(this.y),this}roundToZero(){return this.x=Math.trunc(this.x),this.y=Math.trunc(this.y),this}negate(){return this.x=-this.x,this.y=-this.y,this}dot(e){return this.x*e.x+this.y*e.y}cross(e){return this.x*e.y-this.y*e.x}lengthSq(){return this.x*this.x+this.y*this.y}length(){return Math.sqrt(this.x*this.x+this.y*this.y)}manhattanLength(){return Math.abs(this.x)+Math.abs(this.y)}normalize(){return this.divideScalar(this.length()||1)}angle(){return Math.atan2(-this.y,-this.x)+Math.PI}angleTo(e){let t=Math.sqrt(this.lengthSq()*e.lengthSq());if(t===0)return Math.PI/2;let i=this.dot(e)/t;return Math.acos(gt(i,-1,1))}distanceTo(e){return Math.sqrt(this.distanceToSquared(e))}distanceToSquared(e){let t=this.x-e.x,i=this.y-e.y;return t*t+i*i}manhattanDistanceTo(e){return Math.abs(this.x-e.x)+Math.abs(this.y-e.y)}setLength(e){return this.normalize().multiplyScalar(e)}lerp(e,t){return this.x+=(e.x-this.x)*t,this.y+=(e.y-this.y)*t,this}lerpVectors(e,t,i){return this.x=e.x+(t.x-e.x)*i,this.y=e.y+(t.y-e.y)*i,this}equals(e){return e.x===this.x&&e.y===this.y}fromArray(e,t=0){return this.x=e[t],this.y=e[t+1],this}toArray(e=[],t=0){return e[t]=this.x,e[t+1]=this.y,e}fromBufferAttribute(e,t){return this.x=e.getX(t),this.y=e.getY(t),this}rotateAround(e,t){let i=Math.cos(t),r=Math.sin(t),s=this.x-e.x,o=this.y-e.y;return this.x=s*i-o*r+e.x,this.y=s*r+o*i+e.y,this}random(){return this.x=Math.random(),this.y=Math.random(),this}*[Symbol.iterator](){yield this.x,yield this.y}},Gn=class{constructor(e=0,t=0,i=0,r=1){this.isQuaternion=!0,this._x=e,this._y=t,this._z=i,this._w=r}static slerpFlat(e,t,i,r,s,o,a){let l=i[r+0],c=i[r+1],u=i[r+2],h=i[r+3],f=s[o+0],d=s[o+1],p=s[o+2],x=s[o+3];if(h!==x||l!==f||c!==d||u!==p){let m=l*f+c*d+u*p+h*x;m<0&&(f=-f,d=-d,p=-p,x=-x,m=-m);let g=1-a;if(m<.9995){let v=Math.acos(m),T=Math.sin(v);g=Math.sin(g*v)/T,a=Math.sin(a*v)/T,l=l*g+f*a,c=c*g+d*a,u=u*g+p*a,h=h*g+x*a}else{l=l*g+f*a,c=c*g+d*a,u=u*g+p*a,h=h*g+x*a;let v=1/Math.sqrt(l*l+c*c+u*u+h*h);l*=v,c*=v,u*=v,h*=v}}e[t]=l,e[t+1]=c,e[t+2]=u,e[t+3]=h}static multiplyQuaternionsFlat(e,t,i,r,s,o){let a=i[r],l=i[r+1],c=i[r+2],u=i[r+3],h=s[o],f=s[o+1],d=s[o+2],p=s[o+3];return e[t]=a*p+u*h+l*d-c*f,e[t+1]=l*p+u*f+c*h-a*d,e[t+2]=c*p+u*d+a*f-l*h,e[t+3]=u*p-a*h-l*f-c*d,e}get x(){return this._x}set x(e){this._x=e,this._onChangeCallback()}get y(){return this._y}set y(e){this._y=e,this._onChangeCallback()}get z(){return this._z}set z(e){this._z=e,this._onChangeCallback()}get w(){return this._w}set w(e){this._w=e,this._onChangeCallback()}set(e,t,i,r){return this._x=e,this._y=t,this._z=i,this._w=r,this._onChangeCallback(),this}clone(){return new this.constructor(this._x,this._y,this._z,this._w)}copy(e){return this._x=e.x,this._y=e.y,this._z=e.z,this._w=e.w,this._onChangeCallback(),this}setFromEuler(e,t=!0){let i=e._x,r=e._y,s=e._z,o=e._order,a=Math.cos,l=Math.sin,c=a(i/2),u=a(r/2),h=a(s/2),f=l(i/2),d=l(r/2),p=l(s/2);switch(o){case"XYZ":this._x=f*u*h+c*d*p,this._y=c*d*h-f*u*p,this._z=c*u*p+f*d*h,this._w=c*u*h-f*d*p;break;case"YXZ":this._x=f*u*h+c*d*p,this._y=c*d*h-f*u*p,this._z=c*u*p-f*d*h,this._w=c*u*h+f*d*p;break;case"ZXY":this._x=f*u*h-c*d*p,this._y=c*d*h+f*u*p,this._z=c*u*p+f*d*h,this._w=c*u*h-f*d*p;break;case"ZYX":this._x=f*u*h-c*d*p,this._y=c*d*h+f*u*p,this._z=c*u*p-f*d*h,this._w=c*u*h+f*d*p;break;case"YZX":this._x=f*u*h+c*d*p,this._y=c*d*h+f*u*p,this._z=c*u*p-f*d*h,this._w=c*u*h-f*d*p;break;case"XZY":this._x=f*u*h-c*d*p,this._y=c*d*h-f*u*p,this._z=c*u*p+f*d*h,this._w=c*u*h+f*d*p;break;default:Ke("Quaternion: .setFromEuler() encountered an unknown order: "+o)}return t===!0&&this._onChangeCallback(),this}setFromAxisAngle(e,t){let i=t/2,r=Math.sin(i);return this._x=e.x*r,this._y=e.y*r,this._z=e.z*r,this._w=Math.cos(i),this._onChangeCallback(),this}setFromRotationMatrix(e){let t=e.elements,i=t[0],r=t[4],s=t[8],o=t[1],a=t[5],l=t[9],c=t[2],u=t[6],h=t[10],f=i+a+h;if(f>0){let d=.5/Math.sqrt(f+1);this._w=.25/d,this._x=(u-l)*d,this._y=(s-c)*d,this._z=(o-r)*d}else if(i>a&&i>h){let d=2*Math.sqrt(1+i-a-h);this._w=(u-l)/d,this._x=.25*d,this._y=(r+o)/d,this._z=(s+c)/d}else if(a>h){let d=2*Math.sqrt(1+a-i-h);this._w=(s-c)/d,this._x=(r+o)/d,this._y=.25*d,this._z=(l+u)/d}else{let d=2*Math.sqrt(1+h-i-a);this._w=(o-r)/d,this._x=(s+c)/d,this._y=(l+u)/d,this._z=.25*d}return this._onChangeCallback(),this}setFromUnitVectors(e,t){let i=e.dot(t)+1;return i<1e-8?(i=0,Math.abs(e.x)>Math.abs(e.z)?(this._x=-e.y,this._y=e.x,this._z=0,this._w=i):(this._x=0,this._y=-e.z,this._z=e.y,this._w=i)):(this._x=e.y*t.z-e.z*t.y,this._y=e.z*t.x-e.x*t.z,this._z=e.x*t.y-e.y*t.x,this._w=i),this.normalize()}angleTo(e){return 2*Math.acos(Math.abs(gt(this.dot(e),-1,1)))}rotateTowards(e,t){let i=this.angleTo(e);if(i===0)return this;let r=Math.min(1,t/i);return this.slerp(e,r),this}identity(){return this.set(0,0,0,1)}invert(){return this.conjugate()}conjugate(){return this._x*=-1,this._y*=-1,this._z*=-1,this._onChangeCallback(),this}dot(e){return this._x*e._x+this._y*e._y+this._z*e._z+this._w*e._w}lengthSq(){return this._x*this._x+this._y*this._y+this._z*this._z+this._w*this._w}length(){return Math.sqrt(this._x*this._x+this._y*this._y+this._z*this._z+this._w*this._w)}normalize(){let e=this.length();return e===0?(this._x=0,this._y=0,this._z=0,this._w=1):(e=1/e,this._x=this._x*e,this._y=this._y*e,this._z=this._z*e,this._w=this._w*e),this._onChangeCallback(),this}multiply(e){return this.multiplyQuaternions(this,e)}premultiply(e){return this.multiplyQuaternions(e,this)}multiplyQuaternions(e,t){let i=e._x,r=e._y,s=e._z,o=e._w,a=t._x,l=t._y,c=t._z,u=t._w;return this._x=i*u+o*a+r*c-s*l,this._y=r*u+o*l+s*a-i*c,this._z=s*u+o*c+i*l-r*a,this._w=o*u-i*a-r*l-s*c,this._onChangeCallback(),this}slerp(e,t){let i=e._x,r=e._y,s=e._z,o=e._w,a=this.dot(e);a<0&&(i=-i,r=-r,s=-s,o=-o,a=-a);let l=1-t;if(a<.9995){let c=Math.acos(a),u=Math.sin(c);l=Math.sin(l*c)/u,t=Math.sin(t*c)/u,this._x=this._x*l+i*t,this._y=this._y*l+r*t,this._z=this._z*l+s*t,this._w=this._w*l+o*t,this._onChangeCallback()}else this._x=this._x*l+i*t,this._y=this._y*l+r*t,this._z=this._z*l+s*t,this._w=this._w*l+o*t,this.normalize();return this}slerpQuaternions(e,t,i){return this.copy(e).slerp(t,i)}random(){let e=2*Math.PI*Math.random(),t=2*Math.PI*Math.random(),i=Math.random(),r=Math.sqrt(1-i),s=Math.sqrt(i);return this.set(r*Math.sin(e),r*Math.cos(e),s*Math.sin(t),s*Math.cos(t))}equals(e){return e._x===this._x&&e._y===this._y&&e._z===this._z&&e._w===this._w}fromArray(e,t=0){return this._x=e[t],this._y=e[t+1],this._z=e[t+2],this._w=e[t+3],this._onChangeCallback(),this}toArray(e=[],t=0){return e[t]=this._x,e[t+1]=this._y,e[t+2]=this._z,e[t+3]=this._w,e}fromBufferAttribute(e,t){return this._x=e.getX(t),this._y=e.getY(t),this._z=e.getZ(t),this._w=e.getW(t),this._onChangeCallback(),this}toJSON(){return this.toArray()}_onChange(e){return this._onChangeCallback=e,this}_onChangeCallback(){}*[Symbol.iterator](){yield this._x,yield this._y,yield this._z,yield this._w}},Y=class{static{this.prototype.isVector3=!0}constructor(e=0,t=0,i=0){this.x=e,this.y=t,this.z=i}set(e,t,i){return i===void 0&&(i=this.z),this.x=e,this.y=t,this.z=i,this}setScalar(e){return this.x=e,this.y=e,this.z=e,this}setX(e){return this.x=e,this}setY(e){return this.y=e,this}setZ(e){return this.z=e,this}setComponent(e,t){switch(e){case 0:this.x=t;break;case 1:this.y=t;break;case 2:this.z=t;break;default:throw new Error("THREE.Vector3: index is out of range: "+e)}return this}getComponent(e){switch(e){case 0:return this.x;case 1:return this.y;case 2:return this.z;default:throw new Error("THREE.Vector3: index is out of range: "+e)}}clone(){return new this.constructor(this.x,this.y,this.z)}copy(e){return this.x=e.x,this.y=e.y,this.z=e.z,this}add(e){return this.x+=e.x,this.y+=e.y,this.z+=e.z,this}addScalar(e){return this.x+=e,this.y+=e,this.z+=e,this}addVectors(e,t){return this.x=e.x+t.x,this.y=e.y+t.y,this.z=e.z+t.z,this}addScaledVector(e,t){return this.x+=e.x*t,this.y+=e.y*t,this.z+=e.z*t,this}sub(e){return this.x-=e.x,this.y-=e.y,this.z-=e.z,this}subScalar(e){return this.x-=e,this.y-=e,this.z-=e,this}subVectors(e,t){return this.x=e.x-t.x,this.y=e.y-t.y,this.z=e.z-t.z,this}multiply(e){return this.x*=e.x,this.y*=e.y,this.z*=e.z,this}multiplyScalar(e){return this.x*=e,this.y*=e,this.z*=e,this}multiplyVectors(e,t){return this.x=e.x*t.x,this.y=e.y*t.y,this.z=e.z*t.z,this}applyEuler(e){return this.applyQuaternion(lv.setFromEuler(e))}applyAxisAngle(e,t){return this.applyQuaternion(lv.setFromAxisAngle(e,t))}applyMatrix3(e){let t=this.x,i=this.y,r=this.z,s=e.elements;return this.x=s[0]*t+s[3]*i+s[6]*r,this.y=s[1]*t+s[4]*i+s[7]*r,this.z=s[2]*t+s[5]*i+s[8]*r,this}applyNormalMatrix(e){return this.applyMatrix3(e).normalize()}applyMatrix4(e){let t=this.x,i=this.y,r=this.z,s=e.elements,o=1/(s[3]*t+s[7]*i+s[11]*r+s[15]);return this.x=(s[0]*t+s[4]*i+s[8]*r+s[12])*o,this.y=(s[1]*t+s[5]*i+s[9]*r+s[13])*o,this.z=(s[2]*t+s[6]*i+s[10]*r+s[14])*o,this}applyQuaternion(e){let t=this.x,i=this.y,r=this.z,s=e.x,o=e.y,a=e.z,l=e.w,c=2*(o*r-a*i),u=2*(a*t-s*r),h=2*(s*i-o*t);return this.x=t+l*c+o*h-a*u,this.y=i+l*u+a*c-s*h,this.z=r+l*h+s*u-o*c,this}project(e){return this.applyMatrix4(e.matrixWorldInverse).applyMatrix4(e.projectionMatrix)}unproject(e){return this.applyMatrix4(e.projectionMatrixInverse).applyMatrix4(e.matrixWorld)}transformDirection(e){let t=this.x,i=this.y,r=this.z,s=e.elements;return this.x=s[0]*t+s[4]*i+s[8]*r,this.y=s[1]*t+s[5]*i+s[9]*r,this.z=s[2]*t+s[6]*i+s[10]*r,this.normalize()}divide(e){return this.x/=e.x,this.y/=e.y,this.z/=e.z,this}divideScalar(e){return this.multiplyScalar(1/e)}min(e){return this.x=Math.min(this.x,e.x),this.y=Math.min(this.y,e.y),this.z=Math.min(this.z,e.z),this}max(e){return this.x=Math.max(this.x,e.x),this.y=Math.max(this.y,e.y),this.z=Math.max(this.z,e.z),this}clamp(e,t){return this.x=gt(this.x,e.x,t.x),this.y=gt(this.y,e.y,t.y),this.z=gt(this.z,e.z,t.z),this}clampScalar(e,t){return this.x=gt(this.x,e,t),this.y=gt(this.y,e,t),this.z=gt(this.z,e,t),this}clampLength(e,t){let i=this.length();return this.divideScalar(i||1).multiplyScalar(gt(i,e,t))}floor(){return this.x=Math.floor(this.x),this.y=Math.floor(this.y),this.z=Math.floor(this.z),this}ceil(){return this.x=Math.ceil(this.x),this.y=Math.ceil(this.y),this.z=Math.ceil(this.z),this}round(){return this.x=Math.round(this.x),this.y=Math.round(this.y),this.z=Math.round(this.z),this}roundToZero(){return this.x=Math.trunc(this.x),this.y=Math.trunc(this.y),this.z=Math.trunc(this.z),this}negate(){return this.x=-this.x,this.y=-this.y,this.z=-this.z,this}dot(e){return this.x*e.x+this.y*e.y+this.z*e.z}lengthSq(){return this.x*this.x+this.y*this.y+this.z*this.z}length(){return Math.sqrt(this.x*this.x+this.y*this.y+this.z*this.z)}manhattanLength(){return Math.abs(this.x)+Math.abs(this.y)+Math.abs(this.z)}normalize(){return this.divideScalar(this.length()||1)}setLength(e){return this.normalize().multiplyScalar(e)}lerp(e,t){return this.x+=(e.x-this.x)*t,this.y+=(e.y-this.y)*t,this.z+=(e.z-this.z)*t,this}lerpVectors(e,t,i){return this.x=e.x+(t.x-e.x)*i,this.y=e.y+(t.y-e.y)*i,this.z=e.z+(t.z-e.z)*i,this}cross(e){return this.crossVectors(this,e)}crossVectors(e,t){let i=e.x,r=e.y,s=e.z,o=t.x,a=t.y,l=t.z;return this.x=r*l-s*a,this.y=s*o-i*l,this.z=i*a-r*o,this}projectOnVector(e){let t=e.lengthSq();if(t===0)return this.set(0,0,0);let i=e.dot(this)/t;return this.copy(e).multiplyScalar(i)}projectOnPlane(e){return Rp.copy(this).projectOnVector(e),this.sub(Rp)}reflect(e){return this.sub(Rp.copy(e).multiplyScalar(2*this.dot(e)))}angleTo(e){let t=Math.sqrt(this.lengthSq()*e.lengthSq());if(t===0)return Math.PI/2;let i=this.dot(e)/t;return Math.acos(gt(i,-1,1))}distanceTo(e){return Math.sqrt(this.distanceToSquared(e))}distanceToSquared(e){let t=this.x-e.x,i=this.y-e.y,r=this.z-e.z;return t*t+i*i+r*r}manhattanDistanceTo(e){return Math.abs(this.x-e.x)+Math.abs(this.y-e.y)+Math.abs(this.z-e.z)}setFromSpherical(e){return this.setFromSphericalCoords(e.radius,e.phi,e.theta)}setFromSphericalCoords(e,t,i){let r=Math.sin(t)*e;return this.x=r*Math.sin(i),this.y=Math.cos(t)*e,this.z=r*Math.cos(i),this}setFromCylindrical(e){return this.setFromCylindricalCoords(e.radius,e.theta,e.y)}setFromCylindricalCoords(e,t,i){return this.x=e*Math.sin(t),this.y=i,this.z=e*Math.cos(t),this}setFromMatrixPosition(e){let t=e.elements;return this.x=t[12],this.y=t[13],this.z=t[14],this}setFromMatrixScale(e){let t=this.setFromMatrixColumn(e,0).length(),i=this.setFromMatrixColumn(e,1).length(),r=this.setFromMatrixColumn(e,2).length();return this.x=t,this.y=i,this.z=r,this}setFromMatrixColumn(e,t){return this.fromArray(e.elements,t*4)}setFromMatrix3Column(e,t){return this.fromArray(e.elements,t*3)}setFromEuler(e){return this.x=e._x,this.y=e._y,this.z=e._z,this}setFromColor(e){return this.x=e.r,this.y=e.g,this.z=e.b,this}equals(e){return e.x===this.x&&e.y===this.y&&e.z===this.z}fromArray(e,t=0){return this.x=e[t],this.y=e[t+1],this.z=e[t+2],this}toArray(e=[],t=0){return e[t]=this.x,e[t+1]=this.y,e[t+2]=this.z,e}fromBufferAttribute(e,t){return this.x=e.getX(t),this.y=e.getY(t),this.z=e.getZ(t),this}random(){return this.x=Math.random(),this.y=Math.random(),this.z=Math.random(),this}randomDirection(){let e=Math.random()*Math.PI*2,t=Math.random()*2-1,i=Math.sqrt(1-t*t);return this.x=i*Math.cos(e),this.y=t,this.z=i*Math.sin(e),this}*[Symbol.iterator](){yield this.x,yield this.y,yield this.z}},Rp=new Y,lv=new Gn,rt=class{static{this.prototype.isMatrix3=!0}constructor(e,t,i,r,s,o,a,l,c){this.elements=[1,0,0,0,1,0,0,0,1],e!==void 0&&this.set(e,t,i,r,s,o,a,l,c)}set(e,t,i,r,s,o,a,l,c){let u=this.elements;return u[0]=e,u[1]=r,u[2]=a,u[3]=t,u[4]=s,u[5]=l,u[6]=i,u[7]=o,u[8]=c,this}identity(){return this.set(1,0,0,0,1,0,0,0,1),this}copy(e){let t=this.elements,i=e.elements;return t[0]=i[0],t[1]=i[1],t[2]=i[2],t[3]=i[3],t[4]=i[4],t[5]=i[5],t[6]=i[6],t[7]=i[7],t[8]=i[8],this}extractBasis(e,t,i){return e.setFromMatrix3Column(this,0),t.setFromMatrix3Column(this,1),i.setFromMatrix3Column(this,2),this}setFromMatrix4(e){let t=e.elements;return this.set(t[0],t[4],t[8],t[1],t[5],t[9],t[2],t[6],t[10]),this}multiply(e){return this.multiplyMatrices(this,e)}premultiply(e){return this.multiplyMatrices(e,this)}multiplyMatrices(e,t){let i=e.elements,r=t.elements,s=this.elements,o=i[0],a=i[3],l=i[6],c=i[1],u=i[4],h=i[7],f=i[2],d=i[5],p=i[8],x=r[0],m=r[3],g=r[6],v=r[1],T=r[4],M=r[7],R=r[2],w=r[5],y=r[8];return s[0]=o*x+a*v+l*R,s[3]=o*m+a*T+l*w,s[6]=o*g+a*M+l*y,s[1]=c*x+u*v+h*R,s[4]=c*m+u*T+h*w,s[7]=c*g+u*M+h*y,s[2]=f*x+d*v+p*R,s[5]=f*m+d*T+p*w,s[8]=f*g+d*M+p*y,this}multiplyScalar(e){let t=this.elements;return t[0]*=e,t[3]*=e,t[6]*=e,t[1]*=e,t[4]*=e,t[7]*=e,t[2]*=e,t[5]*=e,t[8]*=e,this}determinant(){let e=this.elements,t=e[0],i=e[1],r=e[2],s=e[3],o=e[4],a=e[5],l=e[6],c=e[7],u=e[8];return t*o*u-t*a*c-i*s*u+i*a*l+r*s*c-r*o*l}invert(){let e=this.elements,t=e[0],i=e[1],r=e[2],s=e[3],o=e[4],a=e[5],l=e[6],c=e[7],u=e[8],h=u*o-a*c,f=a*l-u*s,d=c*s-o*l,p=t*h+i*f+r*d;if(p===0)return this.set(0,0,0,0,0,0,0,0,0);let x=1/p;return e[0]=h*x,e[1]=(r*c-u*i)*x,e[2]=(a*i-r*o)*x,e[3]=f*x,e[4]=(u*t-r*l)*x,e[5]=(r*s-a*t)*x,e[6]=d*x,e[7]=(i*l-c*t)*x,e[8]=(o*t-i*s)*x,this}transpose(){let e,t=this.elements;return e=t[1],t[1]=t[3],t[3]=e,e=t[2],t[2]=t[6],t[6]=e,e=t[5],t[5]=t[7],t[7]=e,this}getNormalMatrix(e){return this.setFromMatrix4(e).invert().transpose()}transposeIntoArray(e){let t=this.elements;return e[0]=t[0],e[1]=t[3],e[2]=t[6],e[3]=t[1],e[4]=t[4],e[5]=t[7],e[6]=t[2],e[7]=t[5],e[8]=t[8],this}setUvTransform(e,t,i,r,s,o,a){let l=Math.cos(s),c=Math.sin(s);return this.set(i*l,i*c,-i*(l*o+c*a)+o+e,-r*c,r*l,-r*(-c*o+l*a)+a+t,0,0,1),this}scale(e,t){return cl("Matrix3: .scale() is deprecated. Use .makeScale() instead."),this.premultiply(Ip.makeScale(e,t)),this}rotate(e){return cl("Matrix3: .rotate() is deprecated. Use .makeRotation() instead."),this.premultiply(Ip.makeRotation(-e)),this}translate(e,t){return cl("Matrix3: .translate() is deprecated. Use .makeTranslation() instead."),this.premultiply(Ip.makeTranslation(e,t)),this}makeTranslation(e,t){return e.isVector2?this.set(1,0,e.x,0,1,e.y,0,0,1):this.set(1,0,e,0,1,t,0,0,1),this}makeRotation(e){let t=Math.cos(e),i=Math.sin(e);return this.set(t,-i,0,i,t,0,0,0,1),this}makeScale(e,t){return this.set(e,0,0,0,t,0,0,0,1),this}equals(e){let t=this.elements,i=e.elements;for(let r=0;r<9;r++)if(t[r]!==i[r])return!1;return!0}fromArray(e,t=0){for(let i=0;i<9;i++)this.elements[i]=e[i+t];return this}toArray(e=[],t=0){let i=this.elements;return e[t]=i[0],e[t+1]=i[1],e[t+2]=i[2],e[t+3]=i[3],e[t+4]=i[4],e[t+5]=i[5],e[t+6]=i[6],e[t+7]=i[7],e[t+8]=i[8],e}clone(){return new this.constructor().fromArray(this.elements)}},Ip=new rt,cv=new rt().set(.4123908,.3575843,.1804808,.212639,.7151687,.0721923,.0193308,.1191948,.9505322),uv=new rt().set(3.2409699,-1.5373832,-.4986108,-.9692436,1.8759675,.0415551,.0556301,-.203977,1.0569715);function z1(){let n={enabled:!0,workingColorSpace:dl,spaces:{},convert:function(r,s,o){return this.enabled===!1||s===o||!s||!o||(this.spaces[s].transfer===Nt&&(r.r=Gr(r.r),r.g=Gr(r.g),r.b=Gr(r.b)),this.spaces[s].primaries!==this.spaces[o].primaries&&(r.applyMatrix3(this.spaces[s].toXYZ),r.applyMatrix3(this.spaces[o].fromXYZ)),this.spaces[o].transfer===Nt&&(r.r=Zo(r.r),r.g=Zo(r.g),r.b=Zo(r.b))),r},workingToColorSpace:function(r,s){return this.convert(r,this.workingColorSpace,s)},colorSpaceToWorking:function(r,s){return this.convert(r,s,this.workingColorSpace)},getPrimaries:function(r){return this.spaces[r].primaries},getTransfer:function(r){return r===Zr?pl:this.spaces[r].transfer},getToneMappingMode:function(r){return this.spaces[r].outputColorSpaceConfig.toneMappingMode||"standard"},getLuminanceCoefficients:function(r,s=this.workingColorSpace){return r.fromArray(this.spaces[s].luminanceCoefficients)},define:function(r){Object.assign(this.spaces,r)},_getMatrix:function(r,s,o){return r.copy(this.spaces[o].fromXYZ).multiply(this.spaces[s].toXYZ)},_getDrawingBufferColorSpace:function(r){return this.spaces[r].outputColorSpaceConfig.drawingBufferColorSpace},_getUnpackColorSpace:function(r=this.workingColorSpace){return this.spaces[r].workingColorSpaceConfig.unpackColorSpace}},e=[.64,.33,.3,.6,.15,.06],t=[.2126,.7152,.0722],i=[.3127,.329];return n.define({[dl]:{primaries:e,whitePoint:i,transfer:pl,toXYZ:cv,fromXYZ:uv,luminanceCoefficients:t,workingColorSpaceConfig:{unpackColorSpace:wi},outputColorSpaceConfig:{drawingBufferColorSpace:wi}},[wi]:{primaries:e,whitePoint:i,transfer:Nt,toXYZ:cv,fromXYZ:uv,luminanceCoefficients:t,outputColorSpaceConfig:{drawingBufferColorSpace:wi}}}),n}var vt=z1();function Gr(n){return n<.04045?n*.0773993808:Math.pow(n*.9478672986+.0521327014,2.4)}function Zo(n){return n<.0031308?n*12.92:1.055*Math.pow(n,.41666)-.055}var Do,$u=class{static getDataURL(e,t="image/png"){if(/^data:/i.test(e.src)||typeof HTMLCanvasElement>"u")return e.src;let i;if(e instanceof HTMLCanvasElement)i=e;else{Do===void 0&&(Do=ml("canvas")),Do.width=e.width,Do.height=e.height;let r=Do.getContext("2d");e instanceof ImageData?r.putImageData(e,0,0):r.drawImage(e,0,0,e.width,e.height),i=Do}return i.toDataURL(t)}static sRGBToLinear(e){if(typeof HTMLImageElement<"u"&&e instanceof HTMLImageElement||typeof HTMLCanvasElement<"u"&&e instanceof HTMLCanvasElement||typeof ImageBitmap<"u"&&e instanceof ImageBitmap){let t=ml("canvas");t.width=e.width,t.height=e.height;let i=t.getContext("2d");i.drawImage(e,0,0,e.width,e.height);let r=i.getImageData(0,0,e.width,e.height),s=r.data;for(let o=0;o<s.length;o++)s[o]=Gr(s[o]/255)*255;return i.putImageData(r,0,0),t}else if(e.data){let t=e.data.slice(0);for(let i=0;i<t.length;i++)t instanceof Uint8Array||t instanceof Uint8ClampedArray?t[i]=Math.floor(Gr(t[i]/255)*255):t[i]=Gr(t[i]);return{data:t,width:e.width,height:e.height}}else return Ke("ImageUtils.sRGBToLinear(): Unsupported image type. No color space conversion applied."),e}},H1=0,jo=class{constructor(e=null){this.isTextureSource=!0,Object.defineProperty(this,"id",{value:H1++}),this.uuid=ha(),this.data=e,this.dataReady=!0,this.version=0}getSize(e){let t=this.data;return typeof HTMLVideoElement<"u"&&t instanceof HTMLVideoElement?e.set(t.videoWidth,t.videoHeight,0):typeof VideoFrame<"u"&&t instanceof VideoFrame?e.set(t.displayWidth,t.displayHeight,0):t!==null?e.set(t.width||0,t.height||0,t.depth||0):e.set(0,0,0),e}set needsUpdate(e){e===!0&&this.version++}toJSON(e){let t=e===void 0||typeof e=="string";if(!t&&e.images[this.uuid]!==void 0)return e.images[this.uuid];let i={uuid:this.uuid,url:""},r=this.data;if(r!==null){let s;if(Array.isArray(r)){s=[];for(let o=0,a=r.length;o<a;o++)r[o].isDataTexture?s.push(Cp(r[o].image)):s.push(Cp(r[o]))}else s=Cp(r);i.url=s}return t||(e.images[this.uuid]=i),i}};function Cp(n){return typeof HTMLImageElement<"u"&&n instanceof HTMLImageElement||typeof HTMLCanvasElement<"u"&&n instanceof HTMLCanvasElement||typeof ImageBitmap<"u"&&n instanceof ImageBitmap?$u.getDataURL(n):n.data?{data:Array.from(n.data),width:n.width,height:n.height,type:n.data.constructor.name}:(Ke("Texture: Unable to serialize Texture."),{})}var W1=0,Np=new Y,fi=class n extends ji{constructor(e=n.DEFAULT_IMAGE,t=n.DEFAULT_MAPPING,i=yr,r=yr,s=li,o=Xr,a=nr,l=di,c=n.DEFAULT_ANISOTROPY,u=Zr){super(),this.isTexture=!0,Object.defineProperty(this,"id",{value:W1++}),this.uuid=ha(),this.name="",this.source=new jo(e),this.mipmaps=[],this.mapping=t,this.channel=0,this.wrapS=i,this.wrapT=r,this.magFilter=s,this.minFilter=o,this.anisotropy=c,this.format=a,this.internalFormat=null,this.type=l,this.offset=new it(0,0),this.repeat=new it(1,1),this.center=new it(0,0),this.rotation=0,this.matrixAutoUpdate=!0,this.matrix=new rt,this.generateMipmaps=!0,this.mipmapsAutoUpdate=!0,this.premultiplyAlpha=!1,this.flipY=!0,this.unpackAlignment=4,this.colorSpace=u,this.userData={},this.updateRanges=[],this.version=0,this.onUpdate=null,this.renderTarget=null,this.isRenderTargetTexture=!1,this.isArrayTexture=!!(e&&e.depth&&e.depth>1),this.pmremVersion=0,this.isPMREMTexture=!1,this.normalized=!1}get width(){return this.source.getSize(Np).x}get height(){return this.source.getSize(Np).y}get depth(){return this.source.getSize(Np).z}get image(){return this.source.data}set image(e){this.source.data=e}updateMatrix(){this.matrix.setUvTransform(this.offset.x,this.offset.y,this.repeat.x,this.repeat.y,this.rotation,this.center.x,this.center.y)}addUpdateRange(e,t){this.updateRanges.push({start:e,count:t})}clearUpdateRanges(){this.updateRanges.length=0}clone(){return new this.constructor().copy(this)}copy(e){return this.name=e.name,this.source=e.source,this.mipmaps=e.mipmaps.slice(0),this.mapping=e.mapping,this.channel=e.channel,this.wrapS=e.wrapS,this.wrapT=e.wrapT,this.magFilter=e.magFilter,this.minFilter=e.minFilter,this.anisotropy=e.anisotropy,this.format=e.format,this.internalFormat=e.internalFormat,this.type=e.type,this.normalized=e.normalized,this.offset.copy(e.offset),this.repeat.copy(e.repeat),this.center.copy(e.center),this.rotation=e.rotation,this.matrixAutoUpdate=e.matrixAutoUpdate,this.matrix.copy(e.matrix),this.generateMipmaps=e.generateMipmaps,this.mipmapsAutoUpdate=e.mipmapsAutoUpdate,this.premultiplyAlpha=e.premultiplyAlpha,this.flipY=e.flipY,this.unpackAlignment=e.unpackAlignment,this.colorSpace=e.colorSpace,this.renderTarget=e.renderTarget,this.isRenderTargetTexture=e.isRenderTargetTexture,this.isPMREMTexture=e.isPMREMTexture,this.isArrayTexture=e.isArrayTexture,this.userData=JSON.parse(JSON.stringify(e.userData)),this.needsUpdate=!0,this}setValues(e){for(let t in e){let i=e[t];if(i===void 0){Ke(`Texture.setValues(): parameter '${t}' has value of undefined.`);continue}let r=this[t];if(r===void 0){Ke(`Texture.setValues(): property '${t}' does not exist.`);continue}r&&i&&r.isVector2&&i.isVector2||r&&i&&r.isVector3&&i.isVector3||r&&i&&r.isMatrix3&&i.isMatrix3?r.copy(i):this[t]=i}}toJSON(e){let t=e===void 0||typeof e=="string";if(!t&&e.textures[this.uuid]!==void 0)return e.textures[this.uuid];let i={metadata:{version:4.7,type:"Texture",generator:"Texture.toJSON"},uuid:this.uuid,name:this.name,image:this.source.toJSON(e).uuid,mapping:this.mapping,channel:this.channel,repeat:[this.repeat.x,this.repeat.y],offset:[this.offset.x,this.offset.y],center:[this.center.x,this.center.y],rotation:this.rotation,wrap:[this.wrapS,this.wrapT],format:this.format,internalFormat:this.internalFormat,type:this.type,normalized:this.normalized,colorSpace:this.colorSpace,minFilter:this.minFilter,magFilter:this.magFilter,anisotropy:this.anisotropy,flipY:this.flipY,generateMipmaps:this.generateMipmaps,mipmapsAutoUpdate:this.mipmapsAutoUpdate,premultiplyAlpha:this.premultiplyAlpha,unpackAlignment:this.unpackAlignment};return Object.keys(this.userData).length>0&&(i.userData=this.userData),t||(e.textures[this.uuid]=i),i}dispose(){this.dispatchEvent({type:"dispose"})}transformUv(e){if(this.mapping!==gm)return e;if(e.applyMatrix3(this.matrix),e.x<0||e.x>1)switch(this.wrapS){case Yu:e.x=e.x-Math.floor(e.x);break;case yr:e.x=e.x<0?0:1;break;case Zu:Math.abs(Math.floor(e.x)%2)===1?e.x=Math.ceil(e.x)-e.x:e.x=e.x-Math.floor(e.x);break}if(e.y<0||e.y>1)switch(this.wrapT){case Yu:e.y=e.y-Math.floor(e.y);break;case yr:e.y=e.y<0?0:1;break;case Zu:Math.abs(Math.floor(e.y)%2)===1?e.y=Math.ceil(e.y)-e.y:e.y=e.y-Math.floor(e.y);break}return this.flipY&&(e.y=1-e.y),e}set needsUpdate(e){e===!0&&(this.version++,this.source.needsUpdate=!0)}set needsPMREMUpdate(e){e===!0&&this.pmremVersion++}};fi.DEFAULT_IMAGE=null;fi.DEFAULT_MAPPING=gm;fi.DEFAULT_ANISOTROPY=1;var jt=class{static{this.prototype.isVector4=!0}constructor(e=0,t=0,i=0,r=1){this.x=e,this.y=t,this.z=i,this.w=r}get width(){return this.z}set width(e){this.z=e}get height(){return this.w}set height(e){this.w=e}set(e,t,i,r){return this.x=e,this.y=t,this.z=i,this.w=r,this}setScalar(e){return this.x=e,this.y=e,this.z=e,this.w=e,this}setX(e){return this.x=e,this}setY(e){return this.y=e,this}setZ(e){return this.z=e,this}setW(e){return this.w=e,this}setComponent(e,t){switch(e){case 0:this.x=t;break;case 1:this.y=t;break;case 2:this.z=t;break;case 3:this.w=t;break;default:throw new Error("THREE.Vector4: index is out of range: "+e)}return this}getComponent(e){switch(e){case 0:return this.x;case 1:return this.y;case 2:return this.z;case 3:return this.w;default:throw new Error("THREE.Vector4: index is out of range: "+e)}}clone(){return new this.constructor(this.x,this.y,this.z,this.w)}copy(e){return this.x=e.x,this.y=e.y,this.z=e.z,this.w=e.w!==void 0?e.w:1,this}add(e){return this.x+=e.x,this.y+=e.y,this.z+=e.z,this.w+=e.w,this}addScalar(e){return this.x+=e,this.y+=e,this.z+=e,this.w+=e,this}addVectors(e,t){return this.x=e.x+t.x,this.y=e.y+t.y,this.z=e.z+t.z,this.w=e.w+t.w,this}addScaledVector(e,t){return this.x+=e.x*t,this.y+=e.y*t,this.z+=e.z*t,this.w+=e.w*t,this}sub(e){return this.x-=e.x,this.y-=e.y,this.z-=e.z,this.w-=e.w,this}subScalar(e){return this.x-=e,this.y-=e,this.z-=e,this.w-=e,this}subVectors(e,t){return this.x=e.x-t.x,this.y=e.y-t.y,this.z=e.z-t.z,this.w=e.w-t.w,this}multiply(e){return this.x*=e.x,this.y*=e.y,this.z*=e.z,this.w*=e.w,this}multiplyScalar(e){return this.x*=e,this.y*=e,this.z*=e,this.w*=e,this}applyMatrix4(e){let t=this.x,i=this.y,r=this.z,s=this.w,o=e.elements;return this.x=o[0]*t+o[4]*i+o[8]*r+o[12]*s,this.y=o[1]*t+o[5]*i+o[9]*r+o[13]*s,this.z=o[2]*t+o[6]*i+o[10]*r+o[14]*s,this.w=o[3]*t+o[7]*i+o[11]*r+o[15]*s,this}divide(e){return this.x/=e.x,this.y/=e.y,this.z/=e.z,this.w/=e.w,this}divideScalar(e){return this.multiplyScalar(1/e)}setAxisAngleFromQuaternion(e){this.w=2*Math.acos(e.w);let t=Math.sqrt(1-e.w*e.w);return t<1e-4?(this.x=1,this.y=0,this.z=0):(this.x=e.x/t,this.y=e.y/t,this.z=e.z/t),this}setAxisAngleFromRotationMatrix(e){let t,i,r,s,l=e.elements,c=l[0],u=l[4],h=l[8],f=l[1],d=l[5],p=l[9],x=l[2],m=l[6],g=l[10];if(Math.abs(u-f)<.01&&Math.abs(h-x)<.01&&Math.abs(p-m)<.01){if(Math.abs(u+f)<.1&&Math.abs(h+x)<.1&&Math.abs(p+m)<.1&&Math.abs(c+d+g-3)<.1)return this.set(1,0,0,0),this;t=Math.PI;let T=(c+1)/2,M=(d+1)/2,R=(g+1)/2,w=(u+f)/4,y=(h+x)/4,A=(p+m)/4;return T>M&&T>R?T<.01?(i=0,r=.707106781,s=.707106781):(i=Math.sqrt(T),r=w/i,s=y/i):M>R?M<.01?(i=.707106781,r=0,s=.707106781):(r=Math.sqrt(M),i=w/r,s=A/r):R<.01?(i=.707106781,r=.707106781,s=0):(s=Math.sqrt(R),i=y/s,r=A/s),this.set(i,r,s,t),this}let v=Math.sqrt((m-p)*(m-p)+(h-x)*(h-x)+(f-u)*(f-u));return Math.abs(v)<.001&&(v=1),this.x=(m-p)/v,this.y=(h-x)/v,this.z=(f-u)/v,this.w=Math.acos((c+d+g-1)/2),this}setFromMatrixPosition(e){let t=e.elements;return this.x=t[12],this.y=t[13],this.z=t[14],this.w=t[15],this}min(e){return this.x=Math.min(this.x,e.x),this.y=Math.min(this.y,e.y),this.z=Math.min(this.z,e.z),this.w=Math.min(this.w,e.w),this}max(e){return this.x=Math.max(this.x,e.x),this.y=Math.max(this.y,e.y),this.z=Math.max(this.z,e.z),this.w=Math.max(this.w,e.w),this}clamp(e,t){return this.x=gt(this.x,e.x,t.x),this.y=gt(this.y,e.y,t.y),this.z=gt(this.z,e.z,t.z),this.w=gt(this.w,e.w,t.w),this}clampScalar(e,t){return this.x=gt(this.x,e,t),this.y=gt(this.y,e,t),this.z=gt(this.z,e,t),this.w=gt(this.w,e,t),this}clampLength(e,t){let i=this.length();return this.divideScalar(i||1).multiplyScalar(gt(i,e,t))}floor(){return this.x=Math.floor(this.x),this.y=Math.floor(this.y),this.z=Math.floor(this.z),this.w=Math.floor(this.w),this}ceil(){return this.x=Math.ceil(this.x),this.y=Math.ceil(this.y),this.z=Math.ceil(this.z),this.w=Math.ceil(this.w),this}round(){return this.x=Math.round(this.x),this.y=Math.round(this.y),this.z=Math.round(this.z),this.w=Math.round(this.w),this}roundToZero(){return this.x=Math.trunc(this.x),this.y=Math.trunc(this.y),this.z=Math.trunc(this.z),this.w=Math.trunc(this.w),this}negate(){return this.x=-this.x,this.y=-this.y,this.z=-this.z,this.w=-this.w,this}dot(e){return this.x*e.x+this.y*e.y+this.z*e.z+this.w*e.w}lengthSq(){return this.x*this.x+this.y*this.y+this.z*this.z+this.w*this.w}length(){return Math.sqrt(this.x*this.x+this.y*this.y+this.z*this.z+this.w*this.w)}manhattanLength(){return Math.abs(this.x)+Math.abs(this.y)+Math.abs(this.z)+Math.abs(this.w)}normalize(){return this.divideScalar(this.length()||1)}setLength(e){return this.normalize().multiplyScalar(e)}lerp(e,t){return this.x+=(e.x-this.x)*t,this.y+=(e.y-this.y)*t,this.z+=(e.z-this.z)*t,this.w+=(e.w-this.w)*t,this}lerpVectors(e,t,i){return this.x=e.x+(t.x-e.x)*i,this.y=e.y+(t.y-e.y)*i,this.z=e.z+(t.z-e.z)*i,this.w=e.w+(t.w-e.w)*i,this}equals(e){return e.x===this.x&&e.y===this.y&&e.z===this.z&&e.w===this.w}fromArray(e,t=0){return this.x=e[t],this.y=e[t+1],this.z=e[t+2],this.w=e[t+3],this}toArray(e=[],t=0){return e[t]=this.x,e[t+1]=this.y,e[t+2]=this.z,e[t+3]=this.w,e}fromBufferAttribute(e,t){return this.x=e.getX(t),this.y=e.getY(t),this.z=e.getZ(t),this.w=e.getW(t),this}random(){return this.x=Math.random(),this.y=Math.random(),this.z=Math.random(),this.w=Math.random(),this}*[Symbol.iterator](){yield this.x,yield this.y,yield this.z,yield this.w}},qu=class extends ji{constructor(e=1,t=1,i={}){super(),i=Object.assign({generateMipmaps:!1,internalFormat:null,minFilter:li,depthBuffer:!0,stencilBuffer:!1,resolveColorBuffer:!0,resolveDepthBuffer:!0,resolveStencilBuffer:!0,storeMultisampledColorBuffer:!0,storeMultisampledDepthBuffer:!0,storeMultisampledStencilBuffer:!0,depthTexture:null,samples:0,count:1,depth:1,multiview:!1,useArrayDepthTexture:!1},i),this.isRenderTarget=!0,this.width=e,this.height=t,this.depth=i.depth,this.scissor=new jt(0,0,e,t),this.scissorTest=!1,this.viewport=new jt(0,0,e,t),this.textures=[];let r=i.count;for(let s=0;s<r;s++)this.textures[s]=new fi({width:e,height:t,depth:i.depth}),this.textures[s].isRenderTargetTexture=!0,this.textures[s].renderTarget=this;this._setTextureOptions(i),this.depthBuffer=i.depthBuffer,this.stencilBuffer=i.stencilBuffer,this.resolveColorBuffer=i.resolveColorBuffer,this.resolveDepthBuffer=i.resolveDepthBuffer,this.resolveStencilBuffer=i.resolveStencilBuffer,this.storeMultisampledColorBuffer=i.storeMultisampledColorBuffer,this.storeMultisampledDepthBuffer=i.storeMultisampledDepthBuffer,this.storeMultisampledStencilBuffer=i.storeMultisampledStencilBuffer,this._depthTexture=null,this.depthTexture=i.depthTexture,this.samples=i.samples,this.multiview=i.multiview,this.useArrayDepthTexture=i.useArrayDepthTexture}_setTextureOptions(e={}){let t={minFilter:li,generateMipmaps:!1,flipY:!1,internalFormat:null};e.mapping!==void 0&&(t.mapping=e.mapping),e.wrapS!==void 0&&(t.wrapS=e.wrapS),e.wrapT!==void 0&&(t.wrapT=e.wrapT),e.wrapR!==void 0&&(t.wrapR=e.wrapR),e.magFilter!==void 0&&(t.magFilter=e.magFilter),e.minFilter!==void 0&&(t.minFilter=e.minFilter),e.format!==void 0&&(t.format=e.format),e.type!==void 0&&(t.type=e.type),e.anisotropy!==void 0&&(t.anisotropy=e.anisotropy),e.colorSpace!==void 0&&(t.colorSpace=e.colorSpace),e.flipY!==void 0&&(t.flipY=e.flipY),e.generateMipmaps!==void 0&&(t.generateMipmaps=e.generateMipmaps),e.mipmapsAutoUpdate!==void 0&&(t.mipmapsAutoUpdate=e.mipmapsAutoUpdate),e.internalFormat!==void 0&&(t.internalFormat=e.internalFormat);for(let i=0;i<this.textures.length;i++)this.textures[i].setValues(t)}get texture(){return this.textures[0]}set texture(e){this.textures[0]=e}set depthTexture(e){this._depthTexture!==null&&this._depthTexture.renderTarget===this&&(this._depthTexture.renderTarget=null),e!==null&&e.renderTarget===null&&(e.renderTarget=this),this._depthTexture=e}get depthTexture(){return this._depthTexture}setSize(e,t,i=1){if(this.width!==e||this.height!==t||this.depth!==i){this.width=e,this.height=t,this.depth=i;for(let r=0,s=this.textures.length;r<s;r++)this.textures[r].image.width=e,this.textures[r].image.height=t,this.textures[r].image.depth=i,this.textures[r].isData3DTexture!==!0&&(this.textures[r].isArrayTexture=this.textures[r].image.depth>1);this.dispose()}this.viewport.set(0,0,e,t),this.scissor.set(0,0,e,t)}clone(){return new this.constructor().copy(this)}copy(e){this.width=e.width,this.height=e.height,this.depth=e.depth,this.scissor.copy(e.scissor),this.scissorTest=e.scissorTest,this.viewport.copy(e.viewport),this.textures.length=0;for(let t=0,i=e.textures.length;t<i;t++){this.textures[t]=e.textures[t].clone(),this.textures[t].isRenderTargetTexture=!0,this.textures[t].renderTarget=this;let r=Object.assign({},e.textures[t].image);this.textures[t].source=new jo(r)}if(this.depthBuffer=e.depthBuffer,this.stencilBuffer=e.stencilBuffer,this.resolveColorBuffer=e.resolveColorBuffer,this.resolveDepthBuffer=e.resolveDepthBuffer,this.resolveStencilBuffer=e.resolveStencilBuffer,this.storeMultisampledColorBuffer=e.storeMultisampledColorBuffer,this.storeMultisampledDepthBuffer=e.storeMultisampledDepthBuffer,this.storeMultisampledStencilBuffer=e.storeMultisampledStencilBuffer,e.depthTexture!==null)if(e.depthTexture.renderTarget===e){let t=e.depthTexture.clone();t.renderTarget=null,this.depthTexture=t}else this.depthTexture=e.depthTexture;else this.depthTexture=null;return this.samples=e.samples,this.multiview=e.multiview,this.useArrayDepthTexture=e.useArrayDepthTexture,this}dispose(){this.dispatchEvent({type:"dispose"})}},Ai=class extends qu{constructor(e=1,t=1,i={}){super(e,t,i),this.isWebGLRenderTarget=!0}},gl=class extends fi{constructor(e=null,t=1,i=1,r=1){super(null),this.isDataArrayTexture=!0,this.image={data:e,width:t,height:i,depth:r},this.magFilter=kn,this.minFilter=kn,this.wrapR=yr,this.generateMipmaps=!1,this.flipY=!1,this.unpackAlignment=1,this.layerUpdates=new Set}copy(e){return super.copy(e),this.wrapR=e.wrapR,this}addLayerUpdate(e){this.layerUpdates.add(e)}clearLayerUpdates(){this.layerUpdates.clear()}};var Ju=class extends fi{constructor(e=null,t=1,i=1,r=1){super(null),this.isData3DTexture=!0,this.image={data:e,width:t,height:i,depth:r},this.magFilter=kn,this.minFilter=kn,this.wrapR=yr,this.generateMipmaps=!1,this.flipY=!1,this.unpackAlignment=1}copy(e){return super.copy(e),this.wrapR=e.wrapR,this}};var Ht=class n{static{this.prototype.isMatrix4=!0}constructor(e,t,i,r,s,o,a,l,c,u,h,f,d,p,x,m){this.elements=[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1],e!==void 0&&this.set(e,t,i,r,s,o,a,l,c,u,h,f,d,p,x,m)}set(e,t,i,r,s,o,a,l,c,u,h,f,d,p,x,m){let g=this.elements;return g[0]=e,g[4]=t,g[8]=i,g[12]=r,g[1]=s,g[5]=o,g[9]=a,g[13]=l,g[2]=c,g[6]=u,g[10]=h,g[14]=f,g[3]=d,g[7]=p,g[11]=x,g[15]=m,this}identity(){return this.set(1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1),this}clone(){return new n().fromArray(this.elements)}copy(e){let t=this.elements,i=e.elements;return t[0]=i[0],t[1]=i[1],t[2]=i[2],t[3]=i[3],t[4]=i[4],t[5]=i[5],t[6]=i[6],t[7]=i[7],t[8]=i[8],t[9]=i[9],t[10]=i[10],t[11]=i[11],t[12]=i[12],t[13]=i[13],t[14]=i[14],t[15]=i[15],this}copyPosition(e){let t=this.elements,i=e.elements;return t[12]=i[12],t[13]=i[13],t[14]=i[14],this}setFromMatrix3(e){let t=e.elements;return this.set(t[0],t[3],t[6],0,t[1],t[4],t[7],0,t[2],t[5],t[8],0,0,0,0,1),this}extractBasis(e,t,i){return this.determinantAffine()===0?(e.set(1,0,0),t.set(0,1,0),i.set(0,0,1),this):(e.setFromMatrixColumn(this,0),t.setFromMatrixColumn(this,1),i.setFromMatrixColumn(this,2),this)}makeBasis(e,t,i){return this.set(e.x,t.x,i.x,0,e.y,t.y,i.y,0,e.z,t.z,i.z,0,0,0,0,1),this}extractRotation(e){if(e.determinantAffine()===0)return this.identity();let t=this.elements,i=e.elements,r=1/Uo.setFromMatrixColumn(e,0).length(),s=1/Uo.setFromMatrixColumn(e,1).length(),o=1/Uo.setFromMatrixColumn(e,2).length();return t[0]=i[0]*r,t[1]=i[1]*r,t[2]=i[2]*r,t[3]=0,t[4]=i[4]*s,t[5]=i[5]*s,t[6]=i[6]*s,t[7]=0,t[8]=i[8]*o,t[9]=i[9]*o,t[10]=i[10]*o,t[11]=0,t[12]=0,t[13]=0,t[14]=0,t[15]=1,this}makeRotationFromEuler(e){let t=this.elements,i=e.x,r=e.y,s=e.z,o=Math.cos(i),a=Math.sin(i),l=Math.cos(r),c=Math.sin(r),u=Math.cos(s),h=Math.sin(s);if(e.order==="XYZ"){let f=o*u,d=o*h,p=a*u,x=a*h;t[0]=l*u,t[4]=-l*h,t[8]=c,t[1]=d+p*c,t[5]=f-x*c,t[9]=-a*l,t[2]=x-f*c,t[6]=p+d*c,t[10]=o*l}else if(e.order==="YXZ"){let f=l*u,d=l*h,p=c*u,x=c*h;t[0]=f+x*a,t[4]=p*a-d,t[8]=o*c,t[1]=o*h,t[5]=o*u,t[9]=-a,t[2]=d*a-p,t[6]=x+f*a,t[10]=o*l}else if(e.order==="ZXY"){let f=l*u,d=l*h,p=c*u,x=c*h;t[0]=f-x*a,t[4]=-o*h,t[8]=p+d*a,t[1]=d+p*a,t[5]=o*u,t[9]=x-f*a,t[2]=-o*c,t[6]=a,t[10]=o*l}else if(e.order==="ZYX"){let f=o*u,d=o*h,p=a*u,x=a*h;t[0]=l*u,t[4]=p*c-d,t[8]=f*c+x,t[1]=l*h,t[5]=x*c+f,t[9]=d*c-p,t[2]=-c,t[6]=a*l,t[10]=o*l}else if(e.order==="YZX"){let f=o*l,d=o*c,p=a*l,x=a*c;t[0]=l*u,t[4]=x-f*h,t[8]=p*h+d,t[1]=h,t[5]=o*u,t[9]=-a*u,t[2]=-c*u,t[6]=d*h+p,t[10]=f-x*h}else if(e.order==="XZY"){let f=o*l,d=o*c,p=a*l,x=a*c;t[0]=l*u,t[4]=-h,t[8]=c*u,t[1]=f*h+x,t[5]=o*u,t[9]=d*h-p,t[2]=p*h-d,t[6]=a*u,t[10]=x*h+f}return t[3]=0,t[7]=0,t[11]=0,t[12]=0,t[13]=0,t[14]=0,t[15]=1,this}makeRotationFromQuaternion(e){return this.compose(X1,e,Y1)}lookAt(e,t,i){let r=this.elements;return Mi.subVectors(e,t),Mi.lengthSq()===0&&(Mi.z=1),Mi.normalize(),os.crossVectors(i,Mi),os.lengthSq()===0&&(Math.abs(i.z)===1?Mi.x+=1e-4:Mi.z+=1e-4,Mi.normalize(),os.crossVectors(i,Mi)),os.normalize(),du.crossVectors(Mi,os),r[0]=os.x,r[4]=du.x,r[8]=Mi.x,r[1]=os.y,r[5]=du.y,r[9]=Mi.y,r[2]=os.z,r[6]=du.z,r[10]=Mi.z,this}multiply(e){return this.multiplyMatrices(this,e)}premultiply(e){return this.multiplyMatrices(e,this)}multiplyMatrices(e,t){let i=e.elements,r=t.elements,s=this.elements,o=i[0],a=i[4],l=i[8],c=i[12],u=i[1],h=i[5],f=i[9],d=i[13],p=i[2],x=i[6],m=i[10],g=i[14],v=i[3],T=i[7],M=i[11],R=i[15],w=r[0],y=r[4],A=r[8],k=r[12],D=r[1],L=r[5],H=r[9],z=r[13],N=r[2],F=r[6],Z=r[10],V=r[14],le=r[3],q=r[7],Q=r[11],ie=r[15];return s[0]=o*w+a*D+l*N+c*le,s[4]=o*y+a*L+l*F+c*q,s[8]=o*A+a*H+l*Z+c*Q,s[12]=o*k+a*z+l*V+c*ie,s[1]=u*w+h*D+f*N+d*le,s[5]=u*y+h*L+f*F+d*q,s[9]=u*A+h*H+f*Z+d*Q,s[13]=u*k+h*z+f*V+d*ie,s[2]=p*w+x*D+m*N+g*le,s[6]=p*y+x*L+m*F+g*q,s[10]=p*A+x*H+m*Z+g*Q,s[14]=p*k+x*z+m*V+g*ie,s[3]=v*w+T*D+M*N+R*le,s[7]=v*y+T*L+M*F+R*q,s[11]=v*A+T*H+M*Z+R*Q,s[15]=v*k+T*z+M*V+R*ie,this}multiplyScalar(e){let t=this.elements;return t[0]*=e,t[4]*=e,t[8]*=e,t[12]*=e,t[1]*=e,t[5]*=e,t[9]*=e,t[13]*=e,t[2]*=e,t[6]*=e,t[10]*=e,t[14]*=e,t[3]*=e,t[7]*=e,t[11]*=e,t[15]*=e,this}determinant(){let e=this.elements,t=e[0],i=e[4],r=e[8],s=e[12],o=e[1],a=e[5],l=e[9],c=e[13],u=e[2],h=e[6],f=e[10],d=e[14],p=e[3],x=e[7],m=e[11],g=e[15],v=l*d-c*f,T=a*d-c*h,M=a*f-l*h,R=o*d-c*u,w=o*f-l*u,y=o*h-a*u;return t*(x*v-m*T+g*M)-i*(p*v-m*R+g*w)+r*(p*T-x*R+g*y)-s*(p*M-x*w+m*y)}determinantAffine(){let e=this.elements,t=e[0],i=e[4],r=e[8],s=e[1],o=e[5],a=e[9],l=e[2],c=e[6],u=e[10];return t*(o*u-a*c)-i*(s*u-a*l)+r*(s*c-o*l)}transpose(){let e=this.elements,t;return t=e[1],e[1]=e[4],e[4]=t,t=e[2],e[2]=e[8],e[8]=t,t=e[6],e[6]=e[9],e[9]=t,t=e[3],e[3]=e[12],e[12]=t,t=e[7],e[7]=e[13],e[13]=t,t=e[11],e[11]=e[14],e[14]=t,this}setPosition(e,t,i){let r=this.elements;return e.isVector3?(r[12]=e.x,r[13]=e.y,r[14]=e.z):(r[12]=e,r[13]=t,r[14]=i),this}invert(){let e=this.elements,t=e[0],i=e[1],r=e[2],s=e[3],o=e[4],a=e[5],l=e[6],c=e[7],u=e[8],h=e[9],f=e[10],d=e[11],p=e[12],x=e[13],m=e[14],g=e[15],v=t*a-i*o,T=t*l-r*o,M=t*c-s*o,R=i*l-r*a,w=i*c-s*a,y=r*c-s*l,A=u*x-h*p,k=u*m-f*p,D=u*g-d*p,L=h*m-f*x,H=h*g-d*x,z=f*g-d*m,N=v*z-T*H+M*L+R*D-w*k+y*A;if(N===0)return this.set(0,0,0,0,0,0,0,0,0,0,0,0,0,0,0,0);let F=1/N;return e[0]=(a*z-l*H+c*L)*F,e[1]=(r*H-i*z-s*L)*F,e[2]=(x*y-m*w+g*R)*F,e[3]=(f*w-h*y-d*R)*F,e[4]=(l*D-o*z-c*k)*F,e[5]=(t*z-r*D+s*k)*F,e[6]=(m*M-p*y-g*T)*F,e[7]=(u*y-f*M+d*T)*F,e[8]=(o*H-a*D+c*A)*F,e[9]=(i*D-t*H-s*A)*F,e[10]=(p*w-x*M+g*v)*F,e[11]=(h*M-u*w-d*v)*F,e[12]=(a*k-o*L-l*A)*F,e[13]=(t*L-i*k+r*A)*F,e[14]=(x*T-p*R-m*v)*F,e[15]=(u*R-h*T+f*v)*F,this}scale(e){let t=this.elements,i=e.x,r=e.y,s=e.z;return t[0]*=i,t[4]*=r,t[8]*=s,t[1]*=i,t[5]*=r,t[9]*=s,t[2]*=i,t[6]*=r,t[10]*=s,t[3]*=i,t[7]*=r,t[11]*=s,this}getMaxScaleOnAxis(){let e=this.elements,t=e[0]*e[0]+e[1]*e[1]+e[2]*e[2],i=e[4]*e[4]+e[5]*e[5]+e[6]*e[6],r=e[8]*e[8]+e[9]*e[9]+e[10]*e[10];return Math.sqrt(Math.max(t,i,r))}makeTranslation(e,t,i){return e.isVector3?this.set(1,0,0,e.x,0,1,0,e.y,0,0,1,e.z,0,0,0,1):this.set(1,0,0,e,0,1,0,t,0,0,1,i,0,0,0,1),this}makeRotationX(e){let t=Math.cos(e),i=Math.sin(e);return this.set(1,0,0,0,0,t,-i,0,0,i,t,0,0,0,0,1),this}makeRotationY(e){let t=Math.cos(e),i=Math.sin(e);return this.set(t,0,i,0,0,1,0,0,-i,0,t,0,0,0,0,1),this}makeRotationZ(e){let t=Math.cos(e),i=Math.sin(e);return this.set(t,-i,0,0,i,t,0,0,0,0,1,0,0,0,0,1),this}makeRotationAxis(e,t){let i=Math.cos(t),r=Math.sin(t),s=1-i,o=e.x,a=e.y,l=e.z,c=s*o,u=s*a;return this.set(c*o+i,c*a-r*l,c*l+r*a,0,c*a+r*l,u*a+i,u*l-r*o,0,c*l-r*a,u*l+r*o,s*l*l+i,0,0,0,0,1),this}makeScale(e,t,i){return this.set(e,0,0,0,0,t,0,0,0,0,i,0,0,0,0,1),this}makeShear(e,t,i,r,s,o){return this.set(1,i,s,0,e,1,o,0,t,r,1,0,0,0,0,1),this}compose(e,t,i){let r=this.elements,s=t._x,o=t._y,a=t._z,l=t._w,c=s+s,u=o+o,h=a+a,f=s*c,d=s*u,p=s*h,x=o*u,m=o*h,g=a*h,v=l*c,T=l*u,M=l*h,R=i.x,w=i.y,y=i.z;return r[0]=(1-(x+g))*R,r[1]=(d+M)*R,r[2]=(p-T)*R,r[3]=0,r[4]=(d-M)*w,r[5]=(1-(f+g))*w,r[6]=(m+v)*w,r[7]=0,r[8]=(p+T)*y,r[9]=(m-v)*y,r[10]=(1-(f+x))*y,r[11]=0,r[12]=e.x,r[13]=e.y,r[14]=e.z,r[15]=1,this}decompose(e,t,i){let r=this.elements;e.x=r[12],e.y=r[13],e.z=r[14];let s=this.determinantAffine();if(s===0)return i.set(1,1,1),t.identity(),this;let o=Uo.set(r[0],r[1],r[2]).length(),a=Uo.set(r[4],r[5],r[6]).length(),l=Uo.set(r[8],r[9],r[10]).length();s<0&&(o=-o),$i.copy(this);let c=1/o,u=1/a,h=1/l;return $i.elements[0]*=c,$i.elements[1]*=c,$i.elements[2]*=c,$i.elements[4]*=u,$i.elements[5]*=u,$i.elements[6]*=u,$i.elements[8]*=h,$i.elements[9]*=h,$i.elements[10]*=h,t.setFromRotationMatrix($i),i.x=o,i.y=a,i.z=l,this}makePerspective(e,t,i,r,s,o,a=Oi,l=!1){let c=this.elements,u=2*s/(t-e),h=2*s/(i-r),f=(t+e)/(t-e),d=(i+r)/(i-r),p,x;if(l)p=s/(o-s),x=o*s/(o-s);else if(a===Oi)p=-(o+s)/(o-s),x=-2*o*s/(o-s);else if(a===$o)p=-o/(o-s),x=-o*s/(o-s);else throw new Error("THREE.Matrix4.makePerspective(): Invalid coordinate system: "+a);return c[0]=u,c[4]=0,c[8]=f,c[12]=0,c[1]=0,c[5]=h,c[9]=d,c[13]=0,c[2]=0,c[6]=0,c[10]=p,c[14]=x,c[3]=0,c[7]=0,c[11]=-1,c[15]=0,this}makeOrthographic(e,t,i,r,s,o,a=Oi,l=!1){let c=this.elements,u=2/(t-e),h=2/(i-r),f=-(t+e)/(t-e),d=-(i+r)/(i-r),p,x;if(l)p=1/(o-s),x=o/(o-s);else if(a===Oi)p=-2/(o-s),x=-(o+s)/(o-s);else if(a===$o)p=-1/(o-s),x=-s/(o-s);else throw new Error("THREE.Matrix4.makeOrthographic(): Invalid coordinate system: "+a);return c[0]=u,c[4]=0,c[8]=0,c[12]=f,c[1]=0,c[5]=h,c[9]=0,c[13]=d,c[2]=0,c[6]=0,c[10]=p,c[14]=x,c[3]=0,c[7]=0,c[11]=0,c[15]=1,this}equals(e){let t=this.elements,i=e.elements;for(let r=0;r<16;r++)if(t[r]!==i[r])return!1;return!0}fromArray(e,t=0){for(let i=0;i<16;i++)this.elements[i]=e[i+t];return this}toArray(e=[],t=0){let i=this.elements;return e[t]=i[0],e[t+1]=i[1],e[t+2]=i[2],e[t+3]=i[3],e[t+4]=i[4],e[t+5]=i[5],e[t+6]=i[6],e[t+7]=i[7],e[t+8]=i[8],e[t+9]=i[9],e[t+10]=i[10],e[t+11]=i[11],e[t+12]=i[12],e[t+13]=i[13],e[t+14]=i[14],e[t+15]=i[15],e}},Uo=new Y,$i=new Ht,X1=new Y(0,0,0),Y1=new Y(1,1,1),os=new Y,du=new Y,Mi=new Y,hv=new Ht,fv=new Gn,Hr=class n{constructor(e=0,t=0,i=0,r=n.DEFAULT_ORDER){this.isEuler=!0,this._x=e,this._y=t,this._z=i,this._order=r}get x(){return this._x}set x(e){this._x=e,this._onChangeCallback()}get y(){return this._y}set y(e){this._y=e,this._onChangeCallback()}get z(){return this._z}set z(e){this._z=e,this._onChangeCallback()}get order(){return this._order}set order(e){this._order=e,this._onChangeCallback()}set(e,t,i,r=this._order){return this._x=e,this._y=t,this._z=i,this._order=r,this._onChangeCallback(),this}clone(){return new this.constructor(this._x,this._y,this._z,this._order)}copy(e){return this._x=e._x,this._y=e._y,this._z=e._z,this._order=e._order,this._onChangeCallback(),this}setFromRotationMatrix(e,t=this._order,i=!0){let r=e.elements,s=r[0],o=r[4],a=r[8],l=r[1],c=r[5],u=r[9],h=r[2],f=r[6],d=r[10];switch(t){case"XYZ":this._y=Math.asin(gt(a,-1,1)),Math.abs(a)<.9999999?(this._x=Math.atan2(-u,d),this._z=Math.atan2(-o,s)):(this._x=Math.atan2(f,c),this._z=0);break;case"YXZ":this._x=Math.asin(-gt(u,-1,1)),Math.abs(u)<.9999999?(this._y=Math.atan2(a,d),this._z=Math.atan2(l,c)):(this._y=Math.atan2(-h,s),this._z=0);break;case"ZXY":this._x=Math.asin(gt(f,-1,1)),Math.abs(f)<.9999999?(this._y=Math.atan2(-h,d),this._z=Math.atan2(-o,c)):(this._y=0,this._z=Math.atan2(l,s));break;case"ZYX":this._y=Math.asin(-gt(h,-1,1)),Math.abs(h)<.9999999?(this._x=Math.atan2(f,d),this._z=Math.atan2(l,s)):(this._x=0,this._z=Math.atan2(-o,c));break;case"YZX":this._z=Math.asin(gt(l,-1,1)),Math.abs(l)<.9999999?(this._x=Math.atan2(-u,c),this._y=Math.atan2(-h,s)):(this._x=0,this._y=Math.atan2(a,d));break;case"XZY":this._z=Math.asin(-gt(o,-1,1)),Math.abs(o)<.9999999?(this._x=Math.atan2(f,c),this._y=Math.atan2(a,s)):(this._x=Math.atan2(-u,d),this._y=0);break;default:Ke("Euler: .setFromRotationMatrix() encountered an unknown order: "+t)}return this._order=t,i===!0&&this._onChangeCallback(),this}setFromQuaternion(e,t,i){return hv.makeRotationFromQuaternion(e),this.setFromRotationMatrix(hv,t,i)}setFromVector3(e,t=this._order){return this.set(e.x,e.y,e.z,t)}reorder(e){return fv.setFromEuler(this),this.setFromQuaternion(fv,e)}equals(e){return e._x===this._x&&e._y===this._y&&e._z===this._z&&e._order===this._order}fromArray(e){return this._x=e[0],this._y=e[1],this._z=e[2],e[3]!==void 0&&(this._order=e[3]),this._onChangeCallback(),this}toArray(e=[],t=0){return e[t]=this._x,e[t+1]=this._y,e[t+2]=this._z,e[t+3]=this._order,e}_onChange(e){return this._onChangeCallback=e,this}_onChangeCallback(){}*[Symbol.iterator](){yield this._x,yield this._y,yield this._z,yield this._order}};Hr.DEFAULT_ORDER="XYZ";var yl=class{constructor(){this.mask=1}set(e){this.mask=(1<<e|0)>>>0}enable(e){this.mask|=1<<e|0}enableAll(){this.mask=-1}toggle(e){this.mask^=1<<e|0}disable(e){this.mask&=~(1<<e|0)}disableAll(){this.mask=0}test(e){return(this.mask&e.mask)!==0}isEnabled(e){return(this.mask&(1<<e|0))!==0}},Z1=0,dv=new Y,Oo=new Gn,Or=new Ht,pu=new Y,rl=new Y,K1=new Y,$1=new Gn,pv=new Y(1,0,0),mv=new Y(0,1,0),gv=new Y(0,0,1),yv={type:"added"},q1={type:"removed"},Fo={type:"childadded",child:null},Pp={type:"childremoved",child:null},zn=class n extends ji{constructor(){super(),this.isObject3D=!0,Object.defineProperty(this,"id",{value:Z1++}),this.uuid=ha(),this.name="",this.type="Object3D",this.parent=null,this.children=[],this.up=n.DEFAULT_UP.clone();let e=new Y,t=new Hr,i=new Gn,r=new Y(1,1,1);function s(){i.setFromEuler(t,!1)}function o(){t.setFromQuaternion(i,void 0,!1)}t._onChange(s),i._onChange(o),Object.defineProperties(this,{position:{configurable:!0,enumerable:!0,value:e},rotation:{configurable:!0,enumerable:!0,value:t},quaternion:{configurable:!0,enumerable:!0,value:i},scale:{configurable:!0,enumerable:!0,value:r},modelViewMatrix:{value:new Ht},normalMatrix:{value:new rt}}),this.matrix=new Ht,this.matrixWorld=new Ht,this.matrixAutoUpdate=n.DEFAULT_MATRIX_AUTO_UPDATE,this.matrixWorldAutoUpdate=n.DEFAULT_MATRIX_WORLD_AUTO_UPDATE,this.matrixWorldNeedsUpdate=!1,this.layers=new yl,this.visible=!0,this.castShadow=!1,this.receiveShadow=!1,this.frustumCulled=!0,this.renderOrder=0,this.animations=[],this.customDepthMaterial=void 0,this.customDistanceMaterial=void 0,this.static=!1,this.userData={},this.pivot=null}onBeforeShadow(){}onAfterShadow(){}onBeforeRender(){}onAfterRender(){}applyMatrix4(e){this.matrixAutoUpdate&&this.updateMatrix(),this.matrix.premultiply(e),this.matrix.decompose(this.position,this.quaternion,this.scale),this.pivot!==null&&this.position.copy(this.pivot).applyMatrix4(this.matrix).sub(this.pivot)}applyQuaternion(e){return this.quaternion.premultiply(e),this}setRotationFromAxisAngle(e,t){this.quaternion.setFromAxisAngle(e,t)}setRotationFromEuler(e){this.quaternion.setFromEuler(e,!0)}setRotationFromMatrix(e){this.quaternion.setFromRotationMatrix(e)}setRotationFromQuaternion(e){this.quaternion.copy(e)}rotateOnAxis(e,t){return Oo.setFromAxisAngle(e,t),this.quaternion.multiply(Oo),this}rotateOnWorldAxis(e,t){return Oo.setFromAxisAngle(e,t),this.quaternion.premultiply(Oo),this}rotateX(e){return this.rotateOnAxis(pv,e)}rotateY(e){return this.rotateOnAxis(mv,e)}rotateZ(e){return this.rotateOnAxis(gv,e)}translateOnAxis(e,t){return dv.copy(e).applyQuaternion(this.quaternion),this.position.add(dv.multiplyScalar(t)),this}translateX(e){return this.translateOnAxis(pv,e)}translateY(e){return this.translateOnAxis(mv,e)}translateZ(e){return this.translateOnAxis(gv,e)}localToWorld(e){return this.updateWorldMatrix(!0,!1),e.applyMatrix4(this.matrixWorld)}worldToLocal(e){return this.updateWorldMatrix(!0,!1),e.applyMatrix4(Or.copy(this.matrixWorld).invert())}lookAt(e,t,i){e.isVector3?pu.copy(e):pu.set(e,t,i);let r=this.parent;this.updateWorldMatrix(!0,!1),rl.setFromMatrixPosition(this.matrixWorld),this.isCamera||this.isLight?Or.lookAt(rl,pu,this.up):Or.lookAt(pu,rl,this.up),this.quaternion.setFromRotationMatrix(Or),r&&(Or.extractRotation(r.matrixWorld),Oo.setFromRotationMatrix(Or),this.quaternion.premultiply(Oo.invert()))}add(e){if(arguments.length>1){for(let t=0;t<arguments.length;t++)this.add(arguments[t]);return this}return e===this?(nt("Object3D.add: object can't be added as a child of itself.",e),this):(e&&e.isObject3D?(e.removeFromParent(),e.parent=this,this.children.push(e),e.dispatchEvent(yv),Fo.child=e,this.dispatchEvent(Fo),Fo.child=null):nt("Object3D.add: object not an instance of THREE.Object3D.",e),this)}remove(e){if(arguments.length>1){for(let i=0;i<arguments.length;i++)this.remove(arguments[i]);return this}let t=this.children.indexOf(e);return t!==-1&&(e.parent=null,this.children.splice(t,1),e.dispatchEvent(q1),Pp.child=e,this.dispatchEvent(Pp),Pp.child=null),this}removeFromParent(){let e=this.parent;return e!==null&&e.remove(this),this}clear(){return this.remove(...this.children)}attach(e){return this.updateWorldMatrix(!0,!1),Or.copy(this.matrixWorld).invert(),e.parent!==null&&(e.parent.updateWorldMatrix(!0,!1),Or.multiply(e.parent.matrixWorld)),e.applyMatrix4(Or),e.removeFromParent(),e.parent=this,this.children.push(e),e.updateWorldMatrix(!1,!0),e.dispatchEvent(yv),Fo.child=e,this.dispatchEvent(Fo),Fo.child=null,this}getObjectById(e){return this.getObjectByProperty("id",e)}getObjectByName(e){return this.getObjectByProperty("name",e)}getObjectByProperty(e,t){if(this[e]===t)return this;for(let i=0,r=this.children.length;i<r;i++){let o=this.children[i].getObjectByProperty(e,t);if(o!==void 0)return o}}getObjectsByProperty(e,t,i=[]){this[e]===t&&i.push(this);let r=this.children;for(let s=0,o=r.length;s<o;s++)r[s].getObjectsByProperty(e,t,i);return i}getWorldPosition(e){return this.updateWorldMatrix(!0,!1),e.setFromMatrixPosition(this.matrixWorld)}getWorldQuaternion(e){return this.updateWorldMatrix(!0,!1),this.matrixWorld.decompose(rl,e,K1),e}getWorldScale(e){return this.updateWorldMatrix(!0,!1),this.matrixWorld.decompose(rl,$1,e),e}getWorldDirection(e){this.updateWorldMatrix(!0,!1);let t=this.matrixWorld.elements;return e.set(t[8],t[9],t[10]).normalize()}raycast(){}intersectsFrustum(){return!0}traverse(e){e(this);let t=this.children;for(let i=0,r=t.length;i<r;i++)t[i].traverse(e)}traverseVisible(e){if(this.visible===!1)return;e(this);let t=this.children;for(let i=0,r=t.length;i<r;i++)t[i].traverseVisible(e)}traverseAncestors(e){let t=this.parent;t!==null&&(e(t),t.traverseAncestors(e))}updateMatrix(){this.matrix.compose(this.position,this.quaternion,this.scale);let e=this.pivot;if(e!==null){let t=e.x,i=e.y,r=e.z,s=this.matrix.elements;s[12]+=t-s[0]*t-s[4]*i-s[8]*r,s[13]+=i-s[1]*t-s[5]*i-s[9]*r,s[14]+=r-s[2]*t-s[6]*i-s[10]*r}this.matrixWorldNeedsUpdate=!0}updateMatrixWorld(e){this.matrixAutoUpdate&&this.updateMatrix(),(this.matrixWorldNeedsUpdate||e)&&(this.matrixWorldAutoUpdate===!0&&(this.parent===null?this.matrixWorld.copy(this.matrix):this.matrixWorld.multiplyMatrices(this.parent.matrixWorld,this.matrix)),this.matrixWorldNeedsUpdate=!1,e=!0);let t=this.children;for(let i=0,r=t.length;i<r;i++)t[i].updateMatrixWorld(e)}updateWorldMatrix(e,t,i=!1){let r=this.parent;if(e===!0&&r!==null&&r.updateWorldMatrix(!0,!1),this.matrixAutoUpdate&&this.updateMatrix(),(this.matrixWorldNeedsUpdate||i)&&(this.matrixWorldAutoUpdate===!0&&(this.parent===null?this.matrixWorld.copy(this.matrix):this.matrixWorld.multiplyMatrices(this.parent.matrixWorld,this.matrix)),this.matrixWorldNeedsUpdate=!1,i=!0),t===!0){let s=this.children;for(let o=0,a=s.length;o<a;o++)s[o].updateWorldMatrix(!1,!0,i)}}toJSON(e){let t=e===void 0||typeof e=="string",i={};t&&(e={geometries:{},materials:{},textures:{},images:{},shapes:{},skeletons:{},animations:{},nodes:{}},i.metadata={version:4.7,type:"Object",generator:"Object3D.toJSON"});let r={};r.uuid=this.uuid,r.type=this.type,r.name=this.name,r.castShadow=this.castShadow,r.receiveShadow=this.receiveShadow,r.visible=this.visible,r.frustumCulled=this.frustumCulled,r.renderOrder=this.renderOrder,r.static=this.static,r.matrixAutoUpdate=this.matrixAutoUpdate,Object.keys(this.userData).length>0&&(r.userData=this.userData),r.layers=this.layers.mask,r.matrix=this.matrix.toArray(),r.up=this.up.toArray(),this.pivot!==null&&(r.pivot=this.pivot.toArray()),this.morphTargetDictionary!==void 0&&(r.morphTargetDictionary=Object.assign({},this.morphTargetDictionary)),this.morphTargetInfluences!==void 0&&(r.morphTargetInfluences=this.morphTargetInfluences.slice()),this.isInstancedMesh&&(r.type="InstancedMesh",r.count=this.count,r.instanceMatrix=this.instanceMatrix.toJSON(),this.instanceColor!==null&&(r.instanceColor=this.instanceColor.toJSON())),this.isBatchedMesh&&(r.type="BatchedMesh",r.perObjectFrustumCulled=this.perObjectFrustumCulled,r.sortObjects=this.sortObjects,r.drawRanges=this._drawRanges,r.reservedRanges=this._reservedRanges,r.geometryInfo=this._geometryInfo.map(a=>({...a,boundingBox:a.boundingBox?a.boundingBox.toJSON():void 0,boundingSphere:a.boundingSphere?a.boundingSphere.toJSON():void 0})),r.instanceInfo=this._instanceInfo.map(a=>({...a})),r.availableInstanceIds=this._availableInstanceIds.slice(),r.availableGeometryIds=this._availableGeometryIds.slice(),r.nextIndexStart=this._nextIndexStart,r.nextVertexStart=this._nextVertexStart,r.geometryCount=this._geometryCount,r.maxInstanceCount=this._maxInstanceCount,r.maxVertexCount=this._maxVertexCount,r.maxIndexCount=this._maxIndexCount,r.geometryInitialized=this._geometryInitialized,r.matricesTexture=this._matricesTexture.toJSON(e),r.indirectTexture=this._indirectTexture.toJSON(e),this._colorsTexture!==null&&(r.colorsTexture=this._colorsTexture.toJSON(e)),this.boundingSphere!==null&&(r.boundingSphere=this.boundingSphere.toJSON()),this.boundingBox!==null&&(r.boundingBox=this.boundingBox.toJSON()));function s(a,l){return a[l.uuid]===void 0&&(a[l.uuid]=l.toJSON(e)),l.uuid}if(this.isScene)this.background&&(this.background.isColor?r.background=this.background.toJSON():this.background.isTexture&&(r.background=this.background.toJSON(e).uuid)),this.environment&&this.environment.isTexture&&this.environment.isRenderTargetTexture!==!0&&(r.environment=this.environment.toJSON(e).uuid);else if(this.isMesh||this.isLine||this.isPoints){r.geometry=s(e.geometries,this.geometry);let a=this.geometry.parameters;if(a!==void 0&&a.shapes!==void 0){let l=a.shapes;if(Array.isArray(l))for(let c=0,u=l.length;c<u;c++){let h=l[c];s(e.shapes,h)}else s(e.shapes,l)}}if(this.isSkinnedMesh&&(r.bindMode=this.bindMode,r.bindMatrix=this.bindMatrix.toArray(),this.skeleton!==void 0&&(s(e.skeletons,this.skeleton),r.skeleton=this.skeleton.uuid)),this.material!==void 0)if(Array.isArray(this.material)){let a=[];for(let l=0,c=this.material.length;l<c;l++)a.push(s(e.materials,this.material[l]));r.material=a}else r.material=s(e.materials,this.material);if(this.children.length>0){r.children=[];for(let a=0;a<this.children.length;a++)r.children.push(this.children[a].toJSON(e).object)}if(this.animations.length>0){r.animations=[];for(let a=0;a<this.animations.length;a++){let l=this.animations[a];r.animations.push(s(e.animations,l))}}if(t){let a=o(e.geometries),l=o(e.materials),c=o(e.textures),u=o(e.images),h=o(e.shapes),f=o(e.skeletons),d=o(e.animations),p=o(e.nodes);a.length>0&&(i.geometries=a),l.length>0&&(i.materials=l),c.length>0&&(i.textures=c),u.length>0&&(i.images=u),h.length>0&&(i.shapes=h),f.length>0&&(i.skeletons=f),d.length>0&&(i.animations=d),p.length>0&&(i.nodes=p)}return i.object=r,i;function o(a){let l=[];for(let c in a){let u=a[c];delete u.metadata,l.push(u)}return l}}clone(e){return new this.constructor().copy(this,e)}copy(e,t=!0){if(this.name=e.name,this.up.copy(e.up),this.position.copy(e.position),this.rotation.order=e.rotation.order,this.quaternion.copy(e.quaternion),this.scale.copy(e.scale),this.pivot=e.pivot!==null?e.pivot.clone():null,this.matrix.copy(e.matrix),this.matrixWorld.copy(e.matrixWorld),this.matrixAutoUpdate=e.matrixAutoUpdate,this.matrixWorldAutoUpdate=e.matrixWorldAutoUpdate,this.matrixWorldNeedsUpdate=e.matrixWorldNeedsUpdate,this.layers.mask=e.layers.mask,this.visible=e.visible,this.castShadow=e.castShadow,this.receiveShadow=e.receiveShadow,this.frustumCulled=e.frustumCulled,this.renderOrder=e.renderOrder,this.static=e.static,this.animations=e.animations.slice(),this.userData=JSON.parse(JSON.stringify(e.userData)),t===!0)for(let i=0;i<e.children.length;i++){let r=e.children[i];this.add(r.clone())}return this}dispose(){this.dispatchEvent({type:"dispose"})}};zn.DEFAULT_UP=new Y(0,1,0);zn.DEFAULT_MATRIX_AUTO_UPDATE=!0;zn.DEFAULT_MATRIX_WORLD_AUTO_UPDATE=!0;var Xs=class extends zn{constructor(){super(),this.isGroup=!0,this.type="Group"}},J1={type:"move"},Qo=class{constructor(){this._targetRay=null,this._grip=null,this._hand=null}getHandSpace(){return this._hand===null&&(this._hand=new Xs,this._hand.matrixAutoUpdate=!1,this._hand.visible=!1,this._hand.joints={},this._hand.inputState={pinching:!1}),this._hand}getTargetRaySpace(){return this._targetRay===null&&(this._targetRay=new Xs,this._targetRay.matrixAutoUpdate=!1,this._targetRay.visible=!1,this._targetRay.hasLinearVelocity=!1,this._targetRay.linearVelocity=new Y,this._targetRay.hasAngularVelocity=!1,this._targetRay.angularVelocity=new Y),this._targetRay}getGripSpace(){return this._grip===null&&(this._grip=new Xs,this._grip.matrixAutoUpdate=!1,this._grip.visible=!1,this._grip.hasLinearVelocity=!1,this._grip.linearVelocity=new Y,this._grip.hasAngularVelocity=!1,this._grip.angularVelocity=new Y,this._grip.eventsEnabled=!1),this._grip}dispatchEvent(e){return this._targetRay!==null&&this._targetRay.dispatchEvent(e),this._grip!==null&&this._grip.dispatchEvent(e),this._hand!==null&&this._hand.dispatchEvent(e),this}connect(e){if(e&&e.hand){let t=this._hand;if(t)for(let i of e.hand.values())this._getHandJoint(t,i)}return this.dispatchEvent({type:"connected",data:e}),this}disconnect(e){return this.dispatchEvent({type:"disconnected",data:e}),this._targetRay!==null&&(this._targetRay.visible=!1),this._grip!==null&&(this._grip.visible=!1),this._hand!==null&&(this._hand.visible=!1),this}update(e,t,i){let r=null,s=null,o=null,a=this._targetRay,l=this._grip,c=this._hand;if(e&&t.session.visibilityState!=="visible-blurred"){if(c&&e.hand){o=!0;for(let x of e.hand.values()){let m=t.getJointPose(x,i),g=this._getHandJoint(c,x);m!==null&&(g.matrix.fromArray(m.transform.matrix),g.matrix.decompose(g.position,g.quaternion,g.scale),g.matrixWorldNeedsUpdate=!0,g.jointRadius=m.radius),g.visible=m!==null}let u=c.joints["index-finger-tip"],h=c.joints["thumb-tip"],f=u.position.distanceTo(h.position),d=.02,p=.005;c.inputState.pinching&&f>d+p?(c.inputState.pinching=!1,this.dispatchEvent({type:"pinchend",handedness:e.handedness,target:this})):!c.inputState.pinching&&f<=d-p&&(c.inputState.pinching=!0,this.dispatchEvent({type:"pinchstart",handedness:e.handedness,target:this}))}else l!==null&&e.gripSpace&&(s=t.getPose(e.gripSpace,i),s!==null&&(l.matrix.fromArray(s.transform.matrix),l.matrix.decompose(l.position,l.quaternion,l.scale),l.matrixWorldNeedsUpdate=!0,s.linearVelocity?(l.hasLinearVelocity=!0,l.linearVelocity.copy(s.linearVelocity)):l.hasLinearVelocity=!1,s.angularVelocity?(l.hasAngularVelocity=!0,l.angularVelocity.copy(s.angularVelocity)):l.hasAngularVelocity=!1,l.eventsEnabled&&l.dispatchEvent({type:"gripUpdated",data:e,target:this})));a!==null&&(r=t.getPose(e.targetRaySpace,i),r===null&&s!==null&&(r=s),r!==null&&(a.matrix.fromArray(r.transform.matrix),a.matrix.decompose(a.position,a.quaternion,a.scale),a.matrixWorldNeedsUpdate=!0,r.linearVelocity?(a.hasLinearVelocity=!0,a.linearVelocity.copy(r.linearVelocity)):a.hasLinearVelocity=!1,r.angularVelocity?(a.hasAngularVelocity=!0,a.angularVelocity.copy(r.angularVelocity)):a.hasAngularVelocity=!1,this.dispatchEvent(J1)))}return a!==null&&(a.visible=r!==null),l!==null&&(l.visible=s!==null),c!==null&&(c.visible=o!==null),this}_getHandJoint(e,t){if(e.joints[t.jointName]===void 0){let i=new Xs;i.matrixAutoUpdate=!1,i.visible=!1,e.joints[t.jointName]=i,e.add(i)}return e.joints[t.jointName]}},xb={aliceblue:15792383,antiquewhite:16444375,aqua:65535,aquamarine:8388564,azure:15794175,beige:16119260,bisque:16770244,black:0,blanchedalmond:16772045,blue:255,blueviolet:9055202,brown:10824234,burlywood:14596231,cadetblue:6266528,chartreuse:8388352,chocolate:13789470,coral:16744272,cornflowerblue:6591981,cornsilk:16775388,crimson:14423100,cyan:65535,darkblue:139,darkcyan:35723,darkgoldenrod:12092939,darkgray:11119017,darkgreen:25600,darkgrey:11119017,darkkhaki:12433259,darkmagenta:9109643,darkolivegreen:5597999,darkorange:16747520,darkorchid:10040012,darkred:9109504,darksalmon:15308410,darkseagreen:9419919,darkslateblue:4734347,darkslategray:3100495,darkslategrey:3100495,darkturquoise:52945,darkviolet:9699539,deeppink:16716947,deepskyblue:49151,dimgray:6908265,dimgrey:6908265,dodgerblue:2003199,firebrick:11674146,floralwhite:16775920,forestgreen:2263842,fuchsia:16711935,gainsboro:14474460,ghostwhite:16316671,gold:16766720,goldenrod:14329120,gray:8421504,green:32768,greenyellow:11403055,grey:8421504,honeydew:15794160,hotpink:16738740,indianred:13458524,indigo:4915330,ivory:16777200,khaki:15787660,lavender:15132410,lavenderblush:16773365,lawngreen:8190976,lemonchiffon:16775885,lightblue:11393254,lightcoral:15761536,lightcyan:14745599,lightgoldenrodyellow:16448210,lightgray:13882323,lightgreen:9498256,lightgrey:13882323,lightpink:16758465,lightsalmon:16752762,lightseagreen:2142890,lightskyblue:8900346,lightslategray:7833753,lightslategrey:7833753,lightsteelblue:11584734,lightyellow:16777184,lime:65280,limegreen:3329330,linen:16445670,magenta:16711935,maroon:8388608,mediumaquamarine:6737322,mediumblue:205,mediumorchid:12211667,mediumpurple:9662683,mediumseagreen:3978097,mediumslateblue:8087790,mediumspringgreen:64154,mediumturquoise:4772300,mediumvioletred:13047173,midnightblue:1644912,mintcream:16121850,mistyrose:16770273,moccasin:16770229,navajowhite:16768685,navy:128,oldlace:16643558,olive:8421376,olivedrab:7048739,orange:16753920,orangered:16729344,orchid:14315734,palegoldenrod:15657130,palegreen:10025880,paleturquoise:11529966,palevioletred:14381203,papayawhip:16773077,peachpuff:16767673,peru:13468991,pink:16761035,plum:14524637,powderblue:11591910,purple:8388736,rebeccapurple:6697881,red:16711680,rosybrown:12357519,royalblue:4286945,saddlebrown:9127187,salmon:16416882,sandybrown:16032864,seagreen:3050327,seashell:16774638,sienna:10506797,silver:12632256,skyblue:8900331,slateblue:6970061,slategray:7372944,slategrey:7372944,snow:16775930,springgreen:65407,steelblue:4620980,tan:13808780,teal:32896,thistle:14204888,tomato:16737095,turquoise:4251856,violet:15631086,wheat:16113331,white:16777215,whitesmoke:16119285,yellow:16776960,yellowgreen:10145074},as={h:0,s:0,l:0},mu={h:0,s:0,l:0};function Lp(n,e,t){return t<0&&(t+=1),t>1&&(t-=1),t<1/6?n+(e-n)*6*t:t<1/2?e:t<2/3?n+(e-n)*6*(2/3-t):n}var ft=class{constructor(e,t,i){return this.isColor=!0,this.r=1,this.g=1,this.b=1,this.set(e,t,i)}set(e,t,i){if(t===void 0&&i===void 0){let r=e;r&&r.isColor?this.copy(r):typeof r=="number"?this.setHex(r):typeof r=="string"&&this.setStyle(r)}else this.setRGB(e,t,i);return this}setScalar(e){return this.r=e,this.g=e,this.b=e,this}setHex(e,t=wi){return e=Math.floor(e),this.r=(e>>16&255)/255,this.g=(e>>8&255)/255,this.b=(e&255)/255,vt.colorSpaceToWorking(this,t),this}setRGB(e,t,i,r=vt.workingColorSpace){return this.r=e,this.g=t,this.b=i,vt.colorSpaceToWorking(this,r),this}setHSL(e,t,i,r=vt.workingColorSpace){if(e=Im(e,1),t=gt(t,0,1),i=gt(i,0,1),t===0)this.r=this.g=this.b=i;else{let s=i<=.5?i*(1+t):i+t-i*t,o=2*i-s;this.r=Lp(o,s,e+1/3),this.g=Lp(o,s,e),this.b=Lp(o,s,e-1/3)}return vt.colorSpaceToWorking(this,r),this}setStyle(e,t=wi){function i(s){s!==void 0&&parseFloat(s)<1&&Ke("Color: Alpha component of "+e+" will be ignored.")}let r;if(r=/^(\w+)\(([^\)]*)\)/.exec(e)){let s,o=r[1],a=r[2];switch(o){case"rgb":case"rgba":if(s=/^\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*(?:,\s*(\d+(?:\.\d+)?|\.\d+)\s*)?$/.exec(a))return i(s[4]),this.setRGB(Math.min(255,parseInt(s[1],10))/255,Math.min(255,parseInt(s[2],10))/255,Math.min(255,parseInt(s[3],10))/255,t);if(s=/^\s*(\d+(?:\.\d+)?|\.\d+)\%\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*(?:,\s*(\d+(?:\.\d+)?|\.\d+)\s*)?$/.exec(a))return i(s[4]),this.setRGB(Math.min(100,parseFloat(s[1]))/100,Math.min(100,parseFloat(s[2]))/100,Math.min(100,parseFloat(s[3]))/100,t);break;case"hsl":case"hsla":if(s=/^\s*([+-]?(?:\d+(?:\.\d+)?|\.\d+))\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*,\s*(\d+(?:\.\d+)?|\.\d+)\%\s*(?:,\s*(\d+(?:\.\d+)?|\.\d+)\s*)?$/.exec(a))return i(s[4]),this.setHSL(parseFloat(s[1])/360,parseFloat(s[2])/100,parseFloat(s[3])/100,t);break;default:Ke("Color: Unknown color model "+e)}}else if(r=/^\#([A-Fa-f\d]+)$/.exec(e)){let s=r[1],o=s.length;if(o===3)return this.setRGB(parseInt(s.charAt(0),16)/15,parseInt(s.charAt(1),16)/15,parseInt(s.charAt(2),16)/15,t);if(o===6)return this.setHex(parseInt(s,16),t);Ke("Color: Invalid hex color "+e)}else if(e&&e.length>0)return this.setColorName(e,t);return this}setColorName(e,t=wi){let i=xb[e.toLowerCase()];return i!==void 0?this.setHex(i,t):Ke("Color: Unknown color "+e),this}clone(){return new this.constructor(this.r,this.g,this.b)}copy(e){return this.r=e.r,this.g=e.g,this.b=e.b,this}copySRGBToLinear(e){return this.r=Gr(e.r),this.g=Gr(e.g),this.b=Gr(e.b),this}copyLinearToSRGB(e){return this.r=Zo(e.r),this.g=Zo(e.g),this.b=Zo(e.b),this}convertSRGBToLinear(){return this.copySRGBToLinear(this),this}convertLinearToSRGB(){return this.copyLinearToSRGB(this),this}getHex(e=wi){return vt.workingToColorSpace(Kn.copy(this),e),Math.round(gt(Kn.r*255,0,255))*65536+Math.round(gt(Kn.g*255,0,255))*256+Math.round(gt(Kn.b*255,0,255))}getHexString(e=wi){return("000000"+this.getHex(e).toString(16)).slice(-6)}getHSL(e,t=vt.workingColorSpace){vt.workingToColorSpace(Kn.copy(this),t);let i=Kn.r,r=Kn.g,s=Kn.b,o=Math.max(i,r,s),a=Math.min(i,r,s),l,c,u=(a+o)/2;if(a===o)l=0,c=0;else{let h=o-a;switch(c=u<=.5?h/(o+a):h/(2-o-a),o){case i:l=(r-s)/h+(r<s?6:0);break;case r:l=(s-i)/h+2;break;case s:l=(i-r)/h+4;break}l/=6}return e.h=l,e.s=c,e.l=u,e}getRGB(e,t=vt.workingColorSpace){return vt.workingToColorSpace(Kn.copy(this),t),e.r=Kn.r,e.g=Kn.g,e.b=Kn.b,e}getStyle(e=wi){vt.workingToColorSpace(Kn.copy(this),e);let t=Kn.r,i=Kn.g,r=Kn.b;return e!==wi?`color(${e} ${t.toFixed(3)} ${i.toFixed(3)} ${r.toFixed(3)})`:`rgb(${Math.round(t*255)},${Math.round(i*255)},${Math.round(r*255)})`}offsetHSL(e,t,i){return this.getHSL(as),this.setHSL(as.h+e,as.s+t,as.l+i)}add(e){return this.r+=e.r,this.g+=e.g,this.b+=e.b,this}addColors(e,t){return this.r=e.r+t.r,this.g=e.g+t.g,this.b=e.b+t.b,this}addScalar(e){return this.r+=e,this.g+=e,this.b+=e,this}sub(e){return this.r=Math.max(0,this.r-e.r),this.g=Math.max(0,this.g-e.g),this.b=Math.max(0,this.b-e.b),this}multiply(e){return this.r*=e.r,this.g*=e.g,this.b*=e.b,this}multiplyScalar(e){return this.r*=e,this.g*=e,this.b*=e,this}lerp(e,t){return this.r+=(e.r-this.r)*t,this.g+=(e.g-this.g)*t,this.b+=(e.b-this.b)*t,this}lerpColors(e,t,i){return this.r=e.r+(t.r-e.r)*i,this.g=e.g+(t.g-e.g)*i,this.b=e.b+(t.b-e.b)*i,this}lerpHSL(e,t){this.getHSL(as),e.getHSL(mu);let i=hl(as.h,mu.h,t),r=hl(as.s,mu.s,t),s=hl(as.l,mu.l,t);return this.setHSL(i,r,s),this}setFromVector3(e){return this.r=e.x,this.g=e.y,this.b=e.z,this}applyMatrix3(e){let t=this.r,i=this.g,r=this.b,s=e.elements;return this.r=s[0]*t+s[3]*i+s[6]*r,this.g=s[1]*t+s[4]*i+s[7]*r,this.b=s[2]*t+s[5]*i+s[8]*r,this}equals(e){return e.r===this.r&&e.g===this.g&&e.b===this.b}fromArray(e,t=0){return this.r=e[t],this.g=e[t+1],this.b=e[t+2],this}toArray(e=[],t=0){return e[t]=this.r,e[t+1]=this.g,e[t+2]=this.b,e}fromBufferAttribute(e,t){return this.r=e.getX(t),this.g=e.getY(t),this.b=e.getZ(t),this}toJSON(){return this.getHex()}*[Symbol.iterator](){yield this.r,yield this.g,yield this.b}},Kn=new ft;ft.NAMES=xb;var _l=class extends zn{constructor(){super(),this.isScene=!0,this.type="Scene",this.background=null,this.environment=null,this.fog=null,this.backgroundBlurriness=0,this.backgroundIntensity=1,this.backgroundRotation=new Hr,this.environmentIntensity=1,this.environmentRotation=new Hr,this.overrideMaterial=null,typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("observe",{detail:this}))}copy(e,t){return super.copy(e,t),this.background=e.background!==null?e.background.clone():null,this.environment=e.environment!==null?e.environment.clone():null,this.fog=e.fog!==null?e.fog.clone():null,this.backgroundBlurriness=e.backgroundBlurriness,this.backgroundIntensity=e.backgroundIntensity,this.backgroundRotation.copy(e.backgroundRotation),this.environmentIntensity=e.environmentIntensity,this.environmentRotation.copy(e.environmentRotation),this.overrideMaterial=e.overrideMaterial!==null?e.overrideMaterial.clone():null,this.matrixAutoUpdate=e.matrixAutoUpdate,this}toJSON(e){let t=super.toJSON(e);return this.fog!==null&&(t.object.fog=this.fog.toJSON()),t.object.backgroundBlurriness=this.backgroundBlurriness,t.object.backgroundIntensity=this.backgroundIntensity,t.object.backgroundRotation=this.backgroundRotation.toArray(),t.object.environmentIntensity=this.environmentIntensity,t.object.environmentRotation=this.environmentRotation.toArray(),t}},qi=new Y,Fr=new Y,Dp=new Y,Br=new Y,Bo=new Y,ko=new Y,_v=new Y,Up=new Y,Op=new Y,Fp=new Y,Bp=new jt,kp=new jt,Vp=new jt,hs=class n{constructor(e=new Y,t=new Y,i=new Y){this.a=e,this.b=t,this.c=i}static getNormal(e,t,i,r){r.subVectors(i,t),qi.subVectors(e,t),r.cross(qi);let s=r.lengthSq();return s>0?r.multiplyScalar(1/Math.sqrt(s)):r.set(0,0,0)}static getBarycoord(e,t,i,r,s){qi.subVectors(r,t),Fr.subVectors(i,t),Dp.subVectors(e,t);let o=qi.dot(qi),a=qi.dot(Fr),l=qi.dot(Dp),c=Fr.dot(Fr),u=Fr.dot(Dp),h=o*c-a*a;if(h===0)return s.set(0,0,0),null;let f=1/h,d=(c*l-a*u)*f,p=(o*u-a*l)*f;return s.set(1-d-p,p,d)}static containsPoint(e,t,i,r){return this.getBarycoord(e,t,i,r,Br)===null?!1:Br.x>=0&&Br.y>=0&&Br.x+Br.y<=1}static getInterpolation(e,t,i,r,s,o,a,l){return this.getBarycoord(e,t,i,r,Br)===null?(l.x=0,l.y=0,"z"in l&&(l.z=0),"w"in l&&(l.w=0),null):(l.setScalar(0),l.addScaledVector(s,Br.x),l.addScaledVector(o,Br.y),l.addScaledVector(a,Br.z),l)}static getInterpolatedAttribute(e,t,i,r,s,o){return Bp.setScalar(0),kp.setScalar(0),Vp.setScalar(0),Bp.fromBufferAttribute(e,t),kp.fromBufferAttribute(e,i),Vp.fromBufferAttribute(e,r),o.setScalar(0),o.addScaledVector(Bp,s.x),o.addScaledVector(kp,s.y),o.addScaledVector(Vp,s.z),o}static isFrontFacing(e,t,i,r){return qi.subVectors(i,t),Fr.subVectors(e,t),qi.cross(Fr).dot(r)<0}set(e,t,i){return this.a.copy(e),this.b.copy(t),this.c.copy(i),this}setFromPointsAndIndices(e,t,i,r){return this.a.copy(e[t]),this.b.copy(e[i]),this.c.copy(e[r]),this}setFromAttributeAndIndices(e,t,i,r){return this.a.fromBufferAttribute(e,t),this.b.fromBufferAttribute(e,i),this.c.fromBufferAttribute(e,r),this}clone(){return new this.constructor().copy(this)}copy(e){return this.a.copy(e.a),this.b.copy(e.b),this.c.copy(e.c),this}getArea(){return qi.subVectors(this.c,this.b),Fr.subVectors(this.a,this.b),qi.cross(Fr).length()*.5}getMidpoint(e){return e.addVectors(this.a,this.b).add(this.c).multiplyScalar(1/3)}getNormal(e){return n.getNormal(this.a,this.b,this.c,e)}getPlane(e){return e.setFromCoplanarPoints(this.a,this.b,this.c)}getBarycoord(e,t){return n.getBarycoord(e,this.a,this.b,this.c,t)}getInterpolation(e,t,i,r,s){return n.getInterpolation(e,this.a,this.b,this.c,t,i,r,s)}containsPoint(e){return n.containsPoint(e,this.a,this.b,this.c)}isFrontFacing(e){return n.isFrontFacing(this.a,this.b,this.c,e)}intersectsBox(e){return e.intersectsTriangle(this)}closestPointToPoint(e,t){let i=this.a,r=this.b,s=this.c,o,a;Bo.subVectors(r,i),ko.subVectors(s,i),Up.subVectors(e,i);let l=Bo.dot(Up),c=ko.dot(Up);if(l<=0&&c<=0)return t.copy(i);Op.subVectors(e,r);let u=Bo.dot(Op),h=ko.dot(Op);if(u>=0&&h<=u)return t.copy(r);let f=l*h-u*c;if(f<=0&&l>=0&&u<=0&&l-u>0)return o=l/(l-u),t.copy(i).addScaledVector(Bo,o);Fp.subVectors(e,s);let d=Bo.dot(Fp),p=ko.dot(Fp);if(p>=0&&d<=p)return t.copy(s);let x=d*c-l*p;if(x<=0&&c>=0&&p<=0)return a=c/(c-p),t.copy(i).addScaledVector(ko,a);let m=u*p-d*h;if(m<=0&&h-u>=0&&d-p>=0)return _v.subVectors(s,r),a=(h-u)/(h-u+(d-p)),t.copy(r).addScaledVector(_v,a);let g=1/(m+x+f);return o=x*g,a=f*g,t.copy(i).addScaledVector(Bo,o).addScaledVector(ko,a)}equals(e){return e.a.equals(this.a)&&e.b.equals(this.b)&&e.c.equals(this.c)}},_r=class{constructor(e=new Y(1/0,1/0,1/0),t=new Y(-1/0,-1/0,-1/0)){this.isBox3=!0,this.min=e,this.max=t}set(e,t){return this.min.copy(e),this.max.copy(t),this}setFromArray(e){this.makeEmpty();for(let t=0,i=e.length;t<i;t+=3)this.expandByPoint(Ji.fromArray(e,t));return this}setFromBufferAttribute(e){this.makeEmpty();for(let t=0,i=e.count;t<i;t++)this.expandByPoint(Ji.fromBufferAttribute(e,t));return this}setFromPoints(e){this.makeEmpty();for(let t=0,i=e.length;t<i;t++)this.expandByPoint(e[t]);return this}setFromCenterAndSize(e,t){let i=Ji.copy(t).multiplyScalar(.5);return this.min.copy(e).sub(i),this.max.copy(e).add(i),this}setFromObject(e,t=!1){return this.makeEmpty(),this.expandByObject(e,t)}clone(){return new this.constructor().copy(this)}copy(e){return this.min.copy(e.min),this.max.copy(e.max),this}makeEmpty(){return this.min.x=this.min.y=this.min.z=1/0,this.max.x=this.max.y=this.max.z=-1/0,this}isEmpty(){return this.max.x<this.min.x||this.max.y<this.min.y||this.max.z<this.min.z}getCenter(e){return this.isEmpty()?e.set(0,0,0):e.addVectors(this.min,this.max).multiplyScalar(.5)}getSize(e){return this.isEmpty()?e.set(0,0,0):e.subVectors(this.max,this.min)}expandByPoint(e){return this.min.min(e),this.max.max(e),this}expandByVector(e){return this.min.sub(e),this.max.add(e),this}expandByScalar(e){return this.min.addScalar(-e),this.max.addScalar(e),this}expandByObject(e,t=!1){e.updateWorldMatrix(!1,!1);let i=e.geometry;if(i!==void 0){let s=i.getAttribute("position");if(t===!0&&s!==void 0&&e.isInstancedMesh!==!0&&e.isBatchedMesh!==!0)for(let o=0,a=s.count;o<a;o++)e.isMesh===!0?e.getVertexPosition(o,Ji):Ji.fromBufferAttribute(s,o),Ji.applyMatrix4(e.matrixWorld),this.expandByPoint(Ji);else e.boundingBox!==void 0?(e.boundingBox===null&&e.computeBoundingBox(),gu.copy(e.boundingBox)):(i.boundingBox===null&&i.computeBoundingBox(),gu.copy(i.boundingBox)),gu.applyMatrix4(e.matrixWorld),this.union(gu)}let r=e.children;for(let s=0,o=r.length;s<o;s++)this.expandByObject(r[s],t);return this}containsPoint(e){return e.x>=this.min.x&&e.x<=this.max.x&&e.y>=this.min.y&&e.y<=this.max.y&&e.z>=this.min.z&&e.z<=this.max.z}containsBox(e){return this.min.x<=e.min.x&&e.max.x<=this.max.x&&this.min.y<=e.min.y&&e.max.y<=this.max.y&&this.min.z<=e.min.z&&e.max.z<=this.max.z}getParameter(e,t){return t.set((e.x-this.min.x)/(this.max.x-this.min.x),(e.y-this.min.y)/(this.max.y-this.min.y),(e.z-this.min.z)/(this.max.z-this.min.z))}intersectsBox(e){return e.max.x>=this.min.x&&e.min.x<=this.max.x&&e.max.y>=this.min.y&&e.min.y<=this.max.y&&e.max.z>=this.min.z&&e.min.z<=this.max.z}intersectsSphere(e){return this.clampPoint(e.center,Ji),Ji.distanceToSquared(e.center)<=e.radius*e.radius}intersectsPlane(e){let t,i;return e.normal.x>0?(t=e.normal.x*this.min.x,i=e.normal.x*this.max.x):(t=e.normal.x*this.max.x,i=e.normal.x*this.min.x),e.normal.y>0?(t+=e.normal.y*this.min.y,i+=e.normal.y*this.max.y):(t+=e.normal.y*this.max.y,i+=e.normal.y*this.min.y),e.normal.z>0?(t+=e.normal.z*this.min.z,i+=e.normal.z*this.max.z):(t+=e.normal.z*this.max.z,i+=e.normal.z*this.min.z),t<=-e.constant&&i>=-e.constant}intersectsTriangle(e){if(this.isEmpty())return!1;this.getCenter(sl),yu.subVectors(this.max,sl),Vo.subVectors(e.a,sl),Go.subVectors(e.b,sl),zo.subVectors(e.c,sl),ls.subVectors(Go,Vo),cs.subVectors(zo,Go),Gs.subVectors(Vo,zo);let t=[0,-ls.z,ls.y,0,-cs.z,cs.y,0,-Gs.z,Gs.y,ls.z,0,-ls.x,cs.z,0,-cs.x,Gs.z,0,-Gs.x,-ls.y,ls.x,0,-cs.y,cs.x,0,-Gs.y,Gs.x,0];return!Gp(t,Vo,Go,zo,yu)||(t=[1,0,0,0,1,0,0,0,1],!Gp(t,Vo,Go,zo,yu))?!1:(_u.crossVectors(ls,cs),t=[_u.x,_u.y,_u.z],Gp(t,Vo,Go,zo,yu))}clampPoint(e,t){return t.copy(e).clamp(this.min,this.max)}distanceToPoint(e){return this.clampPoint(e,Ji).distanceTo(e)}getBoundingSphere(e){return this.isEmpty()?e.makeEmpty():(this.getCenter(e.center),e.radius=this.getSize(Ji).length()*.5),e}intersect(e){return this.min.max(e.min),this.max.min(e.max),this.isEmpty()&&this.makeEmpty(),this}union(e){return this.min.min(e.min),this.max.max(e.max),this}applyMatrix4(e){return this.isEmpty()?this:(kr[0].set(this.min.x,this.min.y,this.min.z).applyMatrix4(e),kr[1].set(this.min.x,this.min.y,this.max.z).applyMatrix4(e),kr[2].set(this.min.x,this.max.y,this.min.z).applyMatrix4(e),kr[3].set(this.min.x,this.max.y,this.max.z).applyMatrix4(e),kr[4].set(this.max.x,this.min.y,this.min.z).applyMatrix4(e),kr[5].set(this.max.x,this.min.y,this.max.z).applyMatrix4(e),kr[6].set(this.max.x,this.max.y,this.min.z).applyMatrix4(e),kr[7].set(this.max.x,this.max.y,this.max.z).applyMatrix4(e),this.setFromPoints(kr),this)}translate(e){return this.min.add(e),this.max.add(e),this}equals(e){return e.min.equals(this.min)&&e.max.equals(this.max)}toJSON(){return{min:this.min.toArray(),max:this.max.toArray()}}fromJSON(e){return this.min.fromArray(e.min),this.max.fromArray(e.max),this}},kr=[new Y,new Y,new Y,new Y,new Y,new Y,new Y,new Y],Ji=new Y,gu=new _r,Vo=new Y,Go=new Y,zo=new Y,ls=new Y,cs=new Y,Gs=new Y,sl=new Y,yu=new Y,_u=new Y,zs=new Y;function Gp(n,e,t,i,r){for(let s=0,o=n.length-3;s<=o;s+=3){zs.fromArray(n,s);let a=r.x*Math.abs(zs.x)+r.y*Math.abs(zs.y)+r.z*Math.abs(zs.z),l=e.dot(zs),c=t.dot(zs),u=i.dot(zs);if(Math.max(-Math.max(l,c,u),Math.min(l,c,u))>a)return!1}return!0}var Mn=new Y,xu=new it,j1=0,$n=class extends ji{constructor(e,t,i=!1){if(super(),Array.isArray(e))throw new TypeError("THREE.BufferAttribute: array should be a Typed Array.");this.isBufferAttribute=!0,Object.defineProperty(this,"id",{value:j1++}),this.name="",this.array=e,this.itemSize=t,this.count=e!==void 0?e.length/t:0,this.normalized=i,this.usage=fb,this.updateRanges=[],this.gpuType=er,this.version=0,this._normalizationScale=e!==void 0?Nm(e):void 0}onUploadCallback(){}set needsUpdate(e){e===!0&&this.version++}setUsage(e){return this.usage=e,this}addUpdateRange(e,t){this.updateRanges.push({start:e,count:t})}clearUpdateRanges(){this.updateRanges.length=0}copy(e){return this.name=e.name,this.array=new e.array.constructor(e.array),this.itemSize=e.itemSize,this.count=e.count,this.normalized=e.normalized,this.usage=e.usage,this.gpuType=e.gpuType,this._normalizationScale=e._normalizationScale,this}copyAt(e,t,i){e*=this.itemSize,i*=t.itemSize;for(let r=0,s=this.itemSize;r<s;r++)this.array[e+r]=t.array[i+r];return this}copyArray(e){return this.array.set(e),this}applyMatrix3(e){if(this.itemSize===2)for(let t=0,i=this.count;t<i;t++)xu.fromBufferAttribute(this,t),xu.applyMatrix3(e),this.setXY(t,xu.x,xu.y);else if(this.itemSize===3)for(let t=0,i=this.count;t<i;t++)Mn.fromBufferAttribute(this,t),Mn.applyMatrix3(e),this.setXYZ(t,Mn.x,Mn.y,Mn.z);return this}applyMatrix4(e){for(let t=0,i=this.count;t<i;t++)Mn.fromBufferAttribute(this,t),Mn.applyMatrix4(e),this.setXYZ(t,Mn.x,Mn.y,Mn.z);return this}applyNormalMatrix(e){for(let t=0,i=this.count;t<i;t++)Mn.fromBufferAttribute(this,t),Mn.applyNormalMatrix(e),this.setXYZ(t,Mn.x,Mn.y,Mn.z);return this}transformDirection(e){for(let t=0,i=this.count;t<i;t++)Mn.fromBufferAttribute(this,t),Mn.transformDirection(e),this.setXYZ(t,Mn.x,Mn.y,Mn.z);return this}set(e,t=0){return this.array.set(e,t),this}getComponent(e,t){let i=this.array[e*this.itemSize+t];return this.normalized&&(i=this._denormalize(i)),i}setComponent(e,t,i){return this.normalized&&(i=this._normalize(i)),this.array[e*this.itemSize+t]=i,this}getX(e){let t=this.array[e*this.itemSize];return this.normalized&&(t=this._denormalize(t)),t}setX(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize]=t,this}getY(e){let t=this.array[e*this.itemSize+1];return this.normalized&&(t=this._denormalize(t)),t}setY(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize+1]=t,this}getZ(e){let t=this.array[e*this.itemSize+2];return this.normalized&&(t=this._denormalize(t)),t}setZ(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize+2]=t,this}getW(e){let t=this.array[e*this.itemSize+3];return this.normalized&&(t=this._denormalize(t)),t}setW(e,t){return this.normalized&&(t=this._normalize(t)),this.array[e*this.itemSize+3]=t,this}setXY(e,t,i){return e*=this.itemSize,this.normalized&&(t=this._normalize(t),i=this._normalize(i)),this.array[e+0]=t,this.array[e+1]=i,this}setXYZ(e,t,i,r){return e*=this.itemSize,this.normalized&&(t=this._normalize(t),i=this._normalize(i),r=this._normalize(r)),this.array[e+0]=t,this.array[e+1]=i,this.array[e+2]=r,this}setXYZW(e,t,i,r,s){return e*=this.itemSize,this.normalized&&(t=this._normalize(t),i=this._normalize(i),r=this._normalize(r),s=this._normalize(s)),this.array[e+0]=t,this.array[e+1]=i,this.array[e+2]=r,this.array[e+3]=s,this}onUpload(e){return this.onUploadCallback=e,this}clone(){return new this.constructor(this.array,this.itemSize).copy(this)}toJSON(){let e={itemSize:this.itemSize,type:this.array.constructor.name,array:Array.from(this.array),normalized:this.normalized};return e.name=this.name,e.usage=this.usage,e.gpuType=this.gpuType,e}dispose(){this.dispatchEvent({type:"dispose"})}_denormalize(e){let t=this._normalizationScale;return t!==void 0?Math.max(e/t,-1):yb(e,this.array)}_normalize(e){let t=this._normalizationScale;return t!==void 0?Math.round(e*t):_b(e,this.array)}};var xl=class extends $n{constructor(e,t,i){super(new Uint16Array(e),t,i)}};var vl=class extends $n{constructor(e,t,i){super(new Uint32Array(e),t,i)}};var qn=class extends $n{constructor(e,t,i){super(new Float32Array(e),t,i)}},Q1=new _r,ol=new Y,zp=new Y,fs=class{constructor(e=new Y,t=-1){this.isSphere=!0,this.center=e,this.radius=t}set(e,t){return this.center.copy(e),this.radius=t,this}setFromPoints(e,t){let i=this.center;t!==void 0?i.copy(t):Q1.setFromPoints(e).getCenter(i);let r=0;for(let s=0,o=e.length;s<o;s++)r=Math.max(r,i.distanceToSquared(e[s]));return this.radius=Math.sqrt(r),this}copy(e){return this.center.copy(e.center),this.radius=e.radius,this}isEmpty(){return this.radius<0}makeEmpty(){return this.center.set(0,0,0),this.radius=-1,this}containsPoint(e){return e.distanceToSquared(this.center)<=this.radius*this.radius}distanceToPoint(e){return e.distanceTo(this.center)-this.radius}intersectsSphere(e){let t=this.radius+e.radius;return e.center.distanceToSquared(this.center)<=t*t}intersectsBox(e){return e.intersectsSphere(this)}intersectsPlane(e){return Math.abs(e.distanceToPoint(this.center))<=this.radius}clampPoint(e,t){let i=this.center.distanceToSquared(e);return t.copy(e),i>this.radius*this.radius&&(t.sub(this.center).normalize(),t.multiplyScalar(this.radius).add(this.center)),t}getBoundingBox(e){return this.isEmpty()?(e.makeEmpty(),e):(e.set(this.center,this.center),e.expandByScalar(this.radius),e)}applyMatrix4(e){return this.center.applyMatrix4(e),this.radius=this.radius*e.getMaxScaleOnAxis(),this}translate(e){return this.center.add(e),this}expandByPoint(e){if(this.isEmpty())return this.center.copy(e),this.radius=0,this;ol.subVectors(e,this.center);let t=ol.lengthSq();if(t>this.radius*this.radius){let i=Math.sqrt(t),r=(i-this.radius)*.5;this.center.addScaledVector(ol,r/i),this.radius+=r}return this}union(e){return e.isEmpty()?this:this.isEmpty()?(this.copy(e),this):(this.center.equals(e.center)===!0?this.radius=Math.max(this.radius,e.radius):(zp.subVectors(e.center,this.center).setLength(e.radius),this.expandByPoint(ol.copy(e.center).add(zp)),this.expandByPoint(ol.copy(e.center).sub(zp))),this)}equals(e){return e.center.equals(this.center)&&e.radius===this.radius}clone(){return new this.constructor().copy(this)}toJSON(){return{radius:this.radius,center:this.center.toArray()}}fromJSON(e){return this.radius=e.radius,this.center.fromArray(e.center),this}},eT=0,Ui=new Ht,Hp=new zn,Ho=new Y,Ei=new _r,al=new _r,Bn=new Y,ci=class n extends ji{constructor(){super(),this.isBufferGeometry=!0,Object.defineProperty(this,"id",{value:eT++}),this.uuid=ha(),this.name="",this.type="BufferGeometry",this.index=null,this.indirect=null,this.indirectOffset=0,this.attributes={},this.morphAttributes={},this.morphTargetsRelative=!1,this.groups=[],this.boundingBox=null,this.boundingSphere=null,this.drawRange={start:0,count:1/0},this.userData={},this._transformed=!1}getIndex(){return this.index}setIndex(e){return Array.isArray(e)?this.index=new(w1(e)?vl:xl)(e,1):this.index=e,this}setIndirect(e,t=0){return this.indirect=e,this.indirectOffset=t,this}getIndirect(){return this.indirect}getAttribute(e){return this.attributes[e]}setAttribute(e,t){return this.attributes[e]=t,this}deleteAttribute(e){return delete this.attributes[e],this}hasAttribute(e){return this.attributes[e]!==void 0}addGroup(e,t,i=0){this.groups.push({start:e,count:t,materialIndex:i})}clearGroups(){this.groups=[]}setDrawRange(e,t){this.drawRange.start=e,this.drawRange.count=t}applyMatrix4(e){let t=this.attributes.position;t!==void 0&&(t.applyMatrix4(e),t.needsUpdate=!0);let i=this.attributes.normal;if(i!==void 0){let s=new rt().getNormalMatrix(e);i.applyNormalMatrix(s),i.needsUpdate=!0}let r=this.attributes.tangent;return r!==void 0&&(r.transformDirection(e),r.needsUpdate=!0),this.boundingBox!==null&&this.computeBoundingBox(),this.boundingSphere!==null&&this.computeBoundingSphere(),this._transformed=!0,this}applyQuaternion(e){return Ui.makeRotationFromQuaternion(e),this.applyMatrix4(Ui),this}rotateX(e){return Ui.makeRotationX(e),this.applyMatrix4(Ui),this}rotateY(e){return Ui.makeRotationY(e),this.applyMatrix4(Ui),this}rotateZ(e){return Ui.makeRotationZ(e),this.applyMatrix4(Ui),this}translate(e,t,i){return Ui.makeTranslation(e,t,i),this.applyMatrix4(Ui),this}scale(e,t,i){return Ui.makeScale(e,t,i),this.applyMatrix4(Ui),this}lookAt(e){return Hp.lookAt(e),Hp.updateMatrix(),this.applyMatrix4(Hp.matrix),this}center(){return this.computeBoundingBox(),this.boundingBox.getCenter(Ho).negate(),this.translate(Ho.x,Ho.y,Ho.z),this}setFromPoints(e){let t=this.getAttribute("position");if(t===void 0){let i=[];for(let r=0,s=e.length;r<s;r++){let o=e[r];i.push(o.x,o.y,o.z||0)}this.setAttribute("position",new qn(i,3))}else{let i=Math.min(e.length,t.count);for(let r=0;r<i;r++){let s=e[r];t.setXYZ(r,s.x,s.y,s.z||0)}e.length>t.count&&Ke("BufferGeometry: Buffer size too small for points data. Use .dispose() and create a new geometry."),t.needsUpdate=!0}return this}computeBoundingBox(){this.boundingBox===null&&(this.boundingBox=new _r);let e=this.attributes.position,t=this.morphAttributes.position;if(e&&e.isGLBufferAttribute){nt("BufferGeometry.computeBoundingBox(): GLBufferAttribute requires a manual bounding box.",this),this.boundingBox.set(new Y(-1/0,-1/0,-1/0),new Y(1/0,1/0,1/0));return}if(e!==void 0){if(this.boundingBox.setFromBufferAttribute(e),t)for(let i=0,r=t.length;i<r;i++){let s=t[i];Ei.setFromBufferAttribute(s),this.morphTargetsRelative?(Bn.addVectors(this.boundingBox.min,Ei.min),this.boundingBox.expandByPoint(Bn),Bn.addVectors(this.boundingBox.max,Ei.max),this.boundingBox.expandByPoint(Bn)):(this.boundingBox.expandByPoint(Ei.min),this.boundingBox.expandByPoint(Ei.max))}}else this.boundingBox.makeEmpty();(isNaN(this.boundingBox.min.x)||isNaN(this.boundingBox.min.y)||isNaN(this.boundingBox.min.z))&&nt('BufferGeometry.computeBoundingBox(): Computed min/max have NaN values. The "position" attribute is likely to have NaN values.',this)}computeBoundingSphere(){this.boundingSphere===null&&(this.boundingSphere=new fs);let e=this.attributes.position,t=this.morphAttributes.position;if(e&&e.isGLBufferAttribute){nt("BufferGeometry.computeBoundingSphere(): GLBufferAttribute requires a manual bounding sphere.",this),this.boundingSphere.set(new Y,1/0);return}if(e){let i=this.boundingSphere.center;if(Ei.setFromBufferAttribute(e),t)for(let s=0,o=t.length;s<o;s++){let a=t[s];al.setFromBufferAttribute(a),this.morphTargetsRelative?(Bn.addVectors(Ei.min,al.min),Ei.expandByPoint(Bn),Bn.addVectors(Ei.max,al.max),Ei.expandByPoint(Bn)):(Ei.expandByPoint(al.min),Ei.expandByPoint(al.max))}Ei.getCenter(i);let r=0;for(let s=0,o=e.count;s<o;s++)Bn.fromBufferAttribute(e,s),r=Math.max(r,i.distanceToSquared(Bn));if(t)for(let s=0,o=t.length;s<o;s++){let a=t[s],l=this.morphTargetsRelative;for(let c=0,u=a.count;c<u;c++)Bn.fromBufferAttribute(a,c),l&&(Ho.fromBufferAttribute(e,c),Bn.add(Ho)),r=Math.max(r,i.distanceToSquared(Bn))}this.boundingSphere.radius=Math.sqrt(r),isNaN(this.boundingSphere.radius)&&nt('BufferGeometry.computeBoundingSphere(): Computed radius is NaN. The "position" attribute is likely to have NaN values.',this)}}computeTangents(){let e=this.index,t=this.attributes;if(e===null||t.position===void 0||t.normal===void 0||t.uv===void 0){nt("BufferGeometry: .computeTangents() failed. Missing required attributes (index, position, normal or uv)");return}let i=t.position,r=t.normal,s=t.uv,o=this.getAttribute("tangent");(o===void 0||o.count!==i.count)&&(o=new $n(new Float32Array(4*i.count),4),this.setAttribute("tangent",o));let a=[],l=[],c=new Uint8Array(i.count);for(let k=0;k<i.count;k++)a[k]=new Y,l[k]=new Y;let u=new Y,h=new Y,f=new Y,d=new it,p=new it,x=new it,m=new Y,g=new Y;function v(k,D,L){c[k]=c[D]=c[L]=1,u.fromBufferAttribute(i,k),h.fromBufferAttribute(i,D),f.fromBufferAttribute(i,L),d.fromBufferAttribute(s,k),p.fromBufferAttribute(s,D),x.fromBufferAttribute(s,L),h.sub(u),f.sub(u),p.sub(d),x.sub(d);let H=1/(p.x*x.y-x.x*p.y);isFinite(H)&&(m.copy(h).multiplyScalar(x.y).addScaledVector(f,-p.y).multiplyScalar(H),g.copy(f).multiplyScalar(p.x).addScaledVector(h,-x.x).multiplyScalar(H),a[k].add(m),a[D].add(m),a[L].add(m),l[k].add(g),l[D].add(g),l[L].add(g))}let T=this.groups;T.length===0&&(T=[{start:0,count:e.count}]);for(let k=0,D=T.length;k<D;++k){let L=T[k],H=L.start,z=L.count;for(let N=H,F=H+z;N<F;N+=3)v(e.getX(N+0),e.getX(N+1),e.getX(N+2))}let M=new Y,R=new Y,w=new Y,y=new Y;function A(k){w.fromBufferAttribute(r,k),y.copy(w);let D=a[k];M.copy(D),M.sub(w.multiplyScalar(w.dot(D))).normalize(),R.crossVectors(y,D);let H=R.dot(l[k])<0?-1:1;o.setXYZW(k,M.x,M.y,M.z,H)}for(let k=0,D=i.count;k<D;++k)c[k]&&A(k);this._transformed=!0}computeVertexNormals(){let e=this.index,t=this.getAttribute("position");if(t!==void 0){let i=this.getAttribute("normal");if(i===void 0||i.count!==t.count)i=new $n(new Float32Array(t.count*3),3),this.setAttribute("normal",i);else for(let f=0,d=i.count;f<d;f++)i.setXYZ(f,0,0,0);let r=new Y,s=new Y,o=new Y,a=new Y,l=new Y,c=new Y,u=new Y,h=new Y;if(e)for(let f=0,d=e.count;f<d;f+=3){let p=e.getX(f+0),x=e.getX(f+1),m=e.getX(f+2);r.fromBufferAttribute(t,p),s.fromBufferAttribute(t,x),o.fromBufferAttribute(t,m),u.subVectors(o,s),h.subVectors(r,s),u.cross(h),a.fromBufferAttribute(i,p),l.fromBufferAttribute(i,x),c.fromBufferAttribute(i,m),a.add(u),l.add(u),c.add(u),i.setXYZ(p,a.x,a.y,a.z),i.setXYZ(x,l.x,l.y,l.z),i.setXYZ(m,c.x,c.y,c.z)}else for(let f=0,d=t.count;f<d;f+=3)r.fromBufferAttribute(t,f+0),s.fromBufferAttribute(t,f+1),o.fromBufferAttribute(t,f+2),u.subVectors(o,s),h.subVectors(r,s),u.cross(h),i.setXYZ(f+0,u.x,u.y,u.z),i.setXYZ(f+1,u.x,u.y,u.z),i.setXYZ(f+2,u.x,u.y,u.z);this.normalizeNormals(),i.needsUpdate=!0}}normalizeNormals(){let e=this.attributes.normal;for(let t=0,i=e.count;t<i;t++)Bn.fromBufferAttribute(e,t),Bn.normalize(),e.setXYZ(t,Bn.x,Bn.y,Bn.z)}toNonIndexed(){function e(a,l){let c=a.array,u=a.itemSize,h=a.normalized,f=new c.constructor(l.length*u),d=0,p=0;for(let x=0,m=l.length;x<m;x++){a.isInterleavedBufferAttribute?d=l[x]*a.data.stride+a.offset:d=l[x]*u;for(let g=0;g<u;g++)f[p++]=c[d++]}return new $n(f,u,h)}if(this.index===null)return Ke("BufferGeometry.toNonIndexed(): BufferGeometry is already non-indexed."),this;let t=new n,i=this.index.array,r=this.attributes;for(let a in r){let l=r[a],c=e(l,i);t.setAttribute(a,c)}let s=this.morphAttributes;for(let a in s){let l=[],c=s[a];for(let u=0,h=c.length;u<h;u++){let f=c[u],d=e(f,i);l.push(d)}t.morphAttributes[a]=l}t.morphTargetsRelative=this.morphTargetsRelative;let o=this.groups;for(let a=0,l=o.length;a<l;a++){let c=o[a];t.addGroup(c.start,c.count,c.materialIndex)}return t}toJSON(){let e={metadata:{version:4.7,type:"BufferGeometry",generator:"BufferGeometry.toJSON"}};if(e.uuid=this.uuid,e.type=this.parameters!==void 0&&this._transformed===!0?"BufferGeometry":this.type,e.name=this.name,Object.keys(this.userData).length>0&&(e.userData=this.userData),this.parameters!==void 0&&this._transformed!==!0){let l=this.parameters;for(let c in l)l[c]!==void 0&&(e[c]=l[c]);return e}e.data={attributes:{}};let t=this.index;t!==null&&(e.data.index={type:t.array.constructor.name,array:Array.prototype.slice.call(t.array)});let i=this.attributes;for(let l in i){let c=i[l];e.data.attributes[l]=c.toJSON(e.data)}let r={},s=!1;for(let l in this.morphAttributes){let c=this.morphAttributes[l],u=[];for(let h=0,f=c.length;h<f;h++){let d=c[h];u.push(d.toJSON(e.data))}u.length>0&&(r[l]=u,s=!0)}s&&(e.data.morphAttributes=r,e.data.morphTargetsRelative=this.morphTargetsRelative);let o=this.groups;o.length>0&&(e.data.groups=JSON.parse(JSON.stringify(o)));let a=this.boundingSphere;return a!==null&&(e.data.boundingSphere=a.toJSON()),e}clone(){return new this.constructor().copy(this)}copy(e){this.index=null,this.attributes={},this.morphAttributes={},this.groups=[],this.boundingBox=null,this.boundingSphere=null;let t={};this.name=e.name;let i=e.index;i!==null&&this.setIndex(i.clone());let r=e.attributes;for(let c in r){let u=r[c];this.setAttribute(c,u.clone(t))}let s=e.morphAttributes;for(let c in s){let u=[],h=s[c];for(let f=0,d=h.length;f<d;f++)u.push(h[f].clone(t));this.morphAttributes[c]=u}this.morphTargetsRelative=e.morphTargetsRelative;let o=e.groups;for(let c=0,u=o.length;c<u;c++){let h=o[c];this.addGroup(h.start,h.count,h.materialIndex)}let a=e.boundingBox;a!==null&&(this.boundingBox=a.clone());let l=e.boundingSphere;return l!==null&&(this.boundingSphere=l.clone()),this.drawRange.start=e.drawRange.start,this.drawRange.count=e.drawRange.count,this.userData=e.userData,this._transformed=e._transformed,this}dispose(){this.dispatchEvent({type:"dispose"})}};var Wp=new Y,tT=new Y,nT=new rt,oi=class{constructor(e=new Y(1,0,0),t=0){this.isPlane=!0,this.normal=e,this.constant=t}set(e,t){return this.normal.copy(e),this.constant=t,this}setComponents(e,t,i,r){return this.normal.set(e,t,i),this.constant=r,this}setFromNormalAndCoplanarPoint(e,t){return this.normal.copy(e),this.constant=-t.dot(this.normal),this}setFromCoplanarPoints(e,t,i){let r=Wp.subVectors(i,t).cross(tT.subVectors(e,t)).normalize();return this.setFromNormalAndCoplanarPoint(r,e),this}copy(e){return this.normal.copy(e.normal),this.constant=e.constant,this}normalize(){let e=1/this.normal.length();return this.normal.multiplyScalar(e),this.constant*=e,this}negate(){return this.constant*=-1,this.normal.negate(),this}distanceToPoint(e){return this.normal.dot(e)+this.constant}distanceToSphere(e){return this.distanceToPoint(e.center)-e.radius}projectPoint(e,t){return t.copy(e).addScaledVector(this.normal,-this.distanceToPoint(e))}intersectLine(e,t,i=!0){let r=e.delta(Wp),s=this.normal.dot(r);if(s===0)return this.distanceToPoint(e.start)===0?t.copy(e.start):null;let o=-(e.start.dot(this.normal)+this.constant)/s;return i===!0&&(o<0||o>1)?null:t.copy(e.start).addScaledVector(r,o)}intersectsLine(e){let t=this.distanceToPoint(e.start),i=this.distanceToPoint(e.end);return t<0&&i>0||i<0&&t>0}intersectsBox(e){return e.intersectsPlane(this)}intersectsSphere(e){return e.intersectsPlane(this)}coplanarPoint(e){return e.copy(this.normal).multiplyScalar(-this.constant)}applyMatrix4(e,t){let i=t||nT.getNormalMatrix(e),r=this.coplanarPoint(Wp).applyMatrix4(e),s=this.normal.applyMatrix3(i).normalize();return this.constant=-r.dot(s),this}translate(e){return this.constant-=e.dot(this.normal),this}equals(e){return e.normal.equals(this.normal)&&e.constant===this.constant}clone(){return new this.constructor().copy(this)}toJSON(){return{normal:this.normal.toArray(),constant:this.constant}}fromJSON(e){return this.normal.fromArray(e.normal),this.constant=e.constant,this}},iT=0,xr=class extends ji{constructor(){super(),this.isMaterial=!0,Object.defineProperty(this,"id",{value:iT++}),this.uuid=ha(),this.name="",this.type="Material",this.blending=la,this.side=vs,this.vertexColors=!1,this.opacity=1,this.transparent=!1,this.alphaHash=!1,this.blendSrc=am,this.blendDst=lm,this.blendEquation=Zs,this.blendSrcAlpha=null,this.blendDstAlpha=null,this.blendEquationAlpha=null,this.blendColor=new ft(0,0,0),this.blendAlpha=0,this.depthFunc=Ko,this.depthTest=!0,this.depthWrite=!0,this.stencilWriteMask=255,this.stencilFunc=ob,this.stencilRef=0,this.stencilFuncMask=255,this.stencilFail=Bu,this.stencilZFail=Bu,this.stencilZPass=Bu,this.stencilWrite=!1,this.clippingPlanes=null,this.clipIntersection=!1,this.clipShadows=!1,this.shadowSide=null,this.colorWrite=!0,this.precision=null,this.polygonOffset=!1,this.polygonOffsetFactor=0,this.polygonOffsetUnits=0,this.dithering=!1,this.alphaToCoverage=!1,this.premultipliedAlpha=!1,this.forceSinglePass=!1,this.allowOverride=!0,this.visible=!0,this.toneMapped=!0,this.userData={},this.version=0,this._alphaTest=0}get alphaTest(){return this._alphaTest}set alphaTest(e){this._alphaTest>0!=e>0&&this.version++,this._alphaTest=e}onBeforeRender(){}onBeforeCompile(){}customProgramCacheKey(){return this.onBeforeCompile.toString()}setValues(e){if(e!==void 0)for(let t in e){let i=e[t];if(i===void 0){Ke(`Material: parameter '${t}' has value of undefined.`);continue}let r=this[t];if(r===void 0){Ke(`Material: '${t}' is not a property of THREE.${this.type}.`);continue}r&&r.isColor?r.set(i):r&&r.isVector2&&i&&i.isVector2||r&&r.isEuler&&i&&i.isEuler||r&&r.isVector3&&i&&i.isVector3?r.copy(i):this[t]=i}}toJSON(e){let t=e===void 0||typeof e=="string";t&&(e={textures:{},images:{}});let i={metadata:{version:4.7,type:"Material",generator:"Material.toJSON"}};i.uuid=this.uuid,i.type=this.type,i.blending=this.blending,i.side=this.side,i.shadowSide=this.shadowSide,i.vertexColors=this.vertexColors,i.opacity=this.opacity,i.transparent=this.transparent,i.blendSrc=this.blendSrc,i.blendDst=this.blendDst,i.blendEquation=this.blendEquation,i.blendSrcAlpha=this.blendSrcAlpha,i.blendDstAlpha=this.blendDstAlpha,i.blendEquationAlpha=this.blendEquationAlpha,i.blendColor=this.blendColor.getHex(),i.blendAlpha=this.blendAlpha,i.depthFunc=this.depthFunc,i.depthTest=this.depthTest,i.depthWrite=this.depthWrite,i.colorWrite=this.colorWrite,i.clipIntersection=this.clipIntersection,i.clipShadows=this.clipShadows,i.stencilWriteMask=this.stencilWriteMask,i.stencilFunc=this.stencilFunc,i.stencilRef=this.stencilRef,i.stencilFuncMask=this.stencilFuncMask,i.stencilFail=this.stencilFail,i.stencilZFail=this.stencilZFail,i.stencilZPass=this.stencilZPass,i.stencilWrite=this.stencilWrite,i.polygonOffset=this.polygonOffset,i.polygonOffsetFactor=this.polygonOffsetFactor,i.polygonOffsetUnits=this.polygonOffsetUnits,i.dithering=this.dithering,i.alphaTest=this.alphaTest,i.alphaHash=this.alphaHash,i.alphaToCoverage=this.alphaToCoverage,i.premultipliedAlpha=this.premultipliedAlpha,i.forceSinglePass=this.forceSinglePass,i.allowOverride=this.allowOverride,i.visible=this.visible,i.toneMapped=this.toneMapped,i.name=this.name,this.color&&this.color.isColor&&(i.color=this.color.getHex()),this.roughness!==void 0&&(i.roughness=this.roughness),this.metalness!==void 0&&(i.metalness=this.metalness),this.sheen!==void 0&&(i.sheen=this.sheen),this.sheenColor&&this.sheenColor.isColor&&(i.sheenColor=this.sheenColor.getHex()),this.sheenRoughness!==void 0&&(i.sheenRoughness=this.sheenRoughness),this.emissive&&this.emissive.isColor&&(i.emissive=this.emissive.getHex()),this.emissiveIntensity!==void 0&&(i.emissiveIntensity=this.emissiveIntensity),this.specular&&this.specular.isColor&&(i.specular=this.specular.getHex()),this.specularIntensity!==void 0&&(i.specularIntensity=this.specularIntensity),this.specularColor&&this.specularColor.isColor&&(i.specularColor=this.specularColor.getHex()),this.shininess!==void 0&&(i.shininess=this.shininess),this.clearcoat!==void 0&&(i.clearcoat=this.clearcoat),this.clearcoatRoughness!==void 0&&(i.clearcoatRoughness=this.clearcoatRoughness),this.diffuseRoughness!==void 0&&(i.diffuseRoughness=this.diffuseRoughness),this.diffuseRoughnessMap&&this.diffuseRoughnessMap.isTexture&&(i.diffuseRoughnessMap=this.diffuseRoughnessMap.toJSON(e).uuid),this.clearcoatMap&&this.clearcoatMap.isTexture&&(i.clearcoatMap=this.clearcoatMap.toJSON(e).uuid),this.clearcoatRoughnessMap&&this.clearcoatRoughnessMap.isTexture&&(i.clearcoatRoughnessMap=this.clearcoatRoughnessMap.toJSON(e).uuid),this.clearcoatNormalMap&&this.clearcoatNormalMap.isTexture&&(i.clearcoatNormalMap=this.clearcoatNormalMap.toJSON(e).uuid,i.clearcoatNormalScale=this.clearcoatNormalScale.toArray()),this.sheenColorMap&&this.sheenColorMap.isTexture&&(i.sheenColorMap=this.sheenColorMap.toJSON(e).uuid),this.sheenRoughnessMap&&this.sheenRoughnessMap.isTexture&&(i.sheenRoughnessMap=this.sheenRoughnessMap.toJSON(e).uuid),this.dispersion!==void 0&&(i.dispersion=this.dispersion),this.retroreflectivity!==void 0&&(i.retroreflectivity=this.retroreflectivity),this.iridescence!==void 0&&(i.iridescence=this.iridescence),this.iridescenceIOR!==void 0&&(i.iridescenceIOR=this.iridescenceIOR),this.iridescenceThicknessMinimum!==void 0&&(i.iridescenceThicknessMinimum=this.iridescenceThicknessMinimum),this.iridescenceThicknessMaximum!==void 0&&(i.iridescenceThicknessMaximum=this.iridescenceThicknessMaximum),this.iridescenceMap&&this.iridescenceMap.isTexture&&(i.iridescenceMap=this.iridescenceMap.toJSON(e).uuid),this.iridescenceThicknessMap&&this.iridescenceThicknessMap.isTexture&&(i.iridescenceThicknessMap=this.iridescenceThicknessMap.toJSON(e).uuid),this.anisotropy!==void 0&&(i.anisotropy=this.anisotropy),this.anisotropyRotation!==void 0&&(i.anisotropyRotation=this.anisotropyRotation),this.anisotropyMap&&this.anisotropyMap.isTexture&&(i.anisotropyMap=this.anisotropyMap.toJSON(e).uuid),this.map&&this.map.isTexture&&(i.map=this.map.toJSON(e).uuid),this.matcap&&this.matcap.isTexture&&(i.matcap=this.matcap.toJSON(e).uuid),this.alphaMap&&this.alphaMap.isTexture&&(i.alphaMap=this.alphaMap.toJSON(e).uuid),this.lightMap&&this.lightMap.isTexture&&(i.lightMap=this.lightMap.toJSON(e).uuid,i.lightMapIntensity=this.lightMapIntensity),this.aoMap&&this.aoMap.isTexture&&(i.aoMap=this.aoMap.toJSON(e).uuid,i.aoMapIntensity=this.aoMapIntensity),this.bumpMap&&this.bumpMap.isTexture&&(i.bumpMap=this.bumpMap.toJSON(e).uuid,i.bumpScale=this.bumpScale),this.normalMap&&this.normalMap.isTexture&&(i.normalMap=this.normalMap.toJSON(e).uuid,i.normalMapType=this.normalMapType,i.normalScale=this.normalScale.toArray()),this.displacementMap&&this.displacementMap.isTexture&&(i.displacementMap=this.displacementMap.toJSON(e).uuid,i.displacementScale=this.displacementScale,i.displacementBias=this.displacementBias),this.roughnessMap&&this.roughnessMap.isTexture&&(i.roughnessMap=this.roughnessMap.toJSON(e).uuid),this.metalnessMap&&this.metalnessMap.isTexture&&(i.metalnessMap=this.metalnessMap.toJSON(e).uuid),this.emissiveMap&&this.emissiveMap.isTexture&&(i.emissiveMap=this.emissiveMap.toJSON(e).uuid),this.specularMap&&this.specularMap.isTexture&&(i.specularMap=this.specularMap.toJSON(e).uuid),this.specularIntensityMap&&this.specularIntensityMap.isTexture&&(i.specularIntensityMap=this.specularIntensityMap.toJSON(e).uuid),this.specularColorMap&&this.specularColorMap.isTexture&&(i.specularColorMap=this.specularColorMap.toJSON(e).uuid),this.envMap&&this.envMap.isTexture&&(i.envMap=this.envMap.toJSON(e).uuid,this.combine!==void 0&&(i.combine=this.combine)),this.envMapRotation!==void 0&&(i.envMapRotation=this.envMapRotation.toArray()),this.envMapIntensity!==void 0&&(i.envMapIntensity=this.envMapIntensity),this.reflectivity!==void 0&&(i.reflectivity=this.reflectivity),this.refractionRatio!==void 0&&(i.refractionRatio=this.refractionRatio),this.gradientMap&&this.gradientMap.isTexture&&(i.gradientMap=this.gradientMap.toJSON(e).uuid),this.transmission!==void 0&&(i.transmission=this.transmission),this.transmissionMap&&this.transmissionMap.isTexture&&(i.transmissionMap=this.transmissionMap.toJSON(e).uuid),this.thickness!==void 0&&(i.thickness=this.thickness),this.thicknessMap&&this.thicknessMap.isTexture&&(i.thicknessMap=this.thicknessMap.toJSON(e).uuid),this.attenuationDistance!==void 0&&(i.attenuationDistance=this.attenuationDistance),this.attenuationColor!==void 0&&(i.attenuationColor=this.attenuationColor.getHex()),this.size!==void 0&&(i.size=this.size),this.sizeAttenuation!==void 0&&(i.sizeAttenuation=this.sizeAttenuation),Array.isArray(this.clippingPlanes)&&this.clippingPlanes.length>0&&(i.clippingPlanes=this.clippingPlanes.map(s=>s.toJSON())),this.rotation!==void 0&&(i.rotation=this.rotation),this.depthPacking!==void 0&&(i.depthPacking=this.depthPacking),this.linewidth!==void 0&&(i.linewidth=this.linewidth),this.linecap!==void 0&&(i.linecap=this.linecap),this.linejoin!==void 0&&(i.linejoin=this.linejoin),this.dashSize!==void 0&&(i.dashSize=this.dashSize),this.gapSize!==void 0&&(i.gapSize=this.gapSize),this.scale!==void 0&&(i.scale=this.scale),this.wireframe!==void 0&&(i.wireframe=this.wireframe),this.wireframeLinewidth!==void 0&&(i.wireframeLinewidth=this.wireframeLinewidth),this.wireframeLinecap!==void 0&&(i.wireframeLinecap=this.wireframeLinecap),this.wireframeLinejoin!==void 0&&(i.wireframeLinejoin=this.wireframeLinejoin),this.flatShading!==void 0&&(i.flatShading=this.flatShading),this.fog!==void 0&&(i.fog=this.fog),Object.keys(this.userData).length>0&&(i.userData=this.userData);function r(s){let o=[];for(let a in s){let l=s[a];delete l.metadata,o.push(l)}return o}if(t){let s=r(e.textures),o=r(e.images);s.length>0&&(i.textures=s),o.length>0&&(i.images=o)}return i}fromJSON(e,t){if(e.uuid!==void 0&&(this.uuid=e.uuid),e.name!==void 0&&(this.name=e.name),e.color!==void 0&&this.color!==void 0&&this.color.setHex(e.color),e.roughness!==void 0&&(this.roughness=e.roughness),e.metalness!==void 0&&(this.metalness=e.metalness),e.sheen!==void 0&&(this.sheen=e.sheen),e.sheenColor!==void 0&&(this.sheenColor=new ft().setHex(e.sheenColor)),e.sheenRoughness!==void 0&&(this.sheenRoughness=e.sheenRoughness),e.emissive!==void 0&&this.emissive!==void 0&&this.emissive.setHex(e.emissive),e.specular!==void 0&&this.specular!==void 0&&this.specular.setHex(e.specular),e.specularIntensity!==void 0&&(this.specularIntensity=e.specularIntensity),e.specularColor!==void 0&&this.specularColor!==void 0&&this.specularColor.setHex(e.specularColor),e.shininess!==void 0&&(this.shininess=e.shininess),e.clearcoat!==void 0&&(this.clearcoat=e.clearcoat),e.clearcoatRoughness!==void 0&&(this.clearcoatRoughness=e.clearcoatRoughness),e.diffuseRoughness!==void 0&&(this.diffuseRoughness=e.diffuseRoughness),e.dispersion!==void 0&&(this.dispersion=e.dispersion),e.retroreflectivity!==void 0&&(this.retroreflectivity=e.retroreflectivity),e.iridescence!==void 0&&(this.iridescence=e.iridescence),e.iridescenceIOR!==void 0&&(this.iridescenceIOR=e.iridescenceIOR),e.iridescenceThicknessMinimum!==void 0&&(this.iridescenceThicknessMinimum=e.iridescenceThicknessMinimum),e.iridescenceThicknessMaximum!==void 0&&(this.iridescenceThicknessMaximum=e.iridescenceThicknessMaximum),e.iridescenceThicknessRange!==void 0&&(this.iridescenceThicknessMinimum=e.iridescenceThicknessRange[0],this.iridescenceThicknessMaximum=e.iridescenceThicknessRange[1]),e.transmission!==void 0&&(this.transmission=e.transmission),e.thickness!==void 0&&(this.thickness=e.thickness),e.attenuationDistance!==void 0&&(this.attenuationDistance=e.attenuationDistance),e.attenuationColor!==void 0&&this.attenuationColor!==void 0&&this.attenuationColor.setHex(e.attenuationColor),e.anisotropy!==void 0&&(this.anisotropy=e.anisotropy),e.anisotropyRotation!==void 0&&(this.anisotropyRotation=e.anisotropyRotation),e.fog!==void 0&&(this.fog=e.fog),e.flatShading!==void 0&&(this.flatShading=e.flatShading),e.blending!==void 0&&(this.blending=e.blending),e.combine!==void 0&&(this.combine=e.combine),e.side!==void 0&&(this.side=e.side),e.shadowSide!==void 0&&(this.shadowSide=e.shadowSide),e.opacity!==void 0&&(this.opacity=e.opacity),e.transparent!==void 0&&(this.transparent=e.transparent),e.alphaTest!==void 0&&(this.alphaTest=e.alphaTest),e.alphaHash!==void 0&&(this.alphaHash=e.alphaHash),e.depthFunc!==void 0&&(this.depthFunc=e.depthFunc),e.depthTest!==void 0&&(this.depthTest=e.depthTest),e.depthWrite!==void 0&&(this.depthWrite=e.depthWrite),e.colorWrite!==void 0&&(this.colorWrite=e.colorWrite),e.clippingPlanes!==void 0&&(this.clippingPlanes=e.clippingPlanes.map(i=>new oi().fromJSON(i))),e.clipIntersection!==void 0&&(this.clipIntersection=e.clipIntersection),e.clipShadows!==void 0&&(this.clipShadows=e.clipShadows),e.depthPacking!==void 0&&(this.depthPacking=e.depthPacking),e.blendSrc!==void 0&&(this.blendSrc=e.blendSrc),e.blendDst!==void 0&&(this.blendDst=e.blendDst),e.blendEquation!==void 0&&(this.blendEquation=e.blendEquation),e.blendSrcAlpha!==void 0&&(this.blendSrcAlpha=e.blendSrcAlpha),e.blendDstAlpha!==void 0&&(this.blendDstAlpha=e.blendDstAlpha),e.blendEquationAlpha!==void 0&&(this.blendEquationAlpha=e.blendEquationAlpha),e.blendColor!==void 0&&this.blendColor!==void 0&&this.blendColor.setHex(e.blendColor),e.blendAlpha!==void 0&&(this.blendAlpha=e.blendAlpha),e.stencilWriteMask!==void 0&&(this.stencilWriteMask=e.stencilWriteMask),e.stencilFunc!==void 0&&(this.stencilFunc=e.stencilFunc),e.stencilRef!==void 0&&(this.stencilRef=e.stencilRef),e.stencilFuncMask!==void 0&&(this.stencilFuncMask=e.stencilFuncMask),e.stencilFail!==void 0&&(this.stencilFail=e.stencilFail),e.stencilZFail!==void 0&&(this.stencilZFail=e.stencilZFail),e.stencilZPass!==void 0&&(this.stencilZPass=e.stencilZPass),e.stencilWrite!==void 0&&(this.stencilWrite=e.stencilWrite),e.wireframe!==void 0&&(this.wireframe=e.wireframe),e.wireframeLinewidth!==void 0&&(this.wireframeLinewidth=e.wireframeLinewidth),e.wireframeLinecap!==void 0&&(this.wireframeLinecap=e.wireframeLinecap),e.wireframeLinejoin!==void 0&&(this.wireframeLinejoin=e.wireframeLinejoin),e.rotation!==void 0&&(this.rotation=e.rotation),e.linewidth!==void 0&&(this.linewidth=e.linewidth),e.linecap!==void 0&&(this.linecap=e.linecap),e.linejoin!==void 0&&(this.linejoin=e.linejoin),e.dashSize!==void 0&&(this.dashSize=e.dashSize),e.gapSize!==void 0&&(this.gapSize=e.gapSize),e.scale!==void 0&&(this.scale=e.scale),e.polygonOffset!==void 0&&(this.polygonOffset=e.polygonOffset),e.polygonOffsetFactor!==void 0&&(this.polygonOffsetFactor=e.polygonOffsetFactor),e.polygonOffsetUnits!==void 0&&(this.polygonOffsetUnits=e.polygonOffsetUnits),e.dithering!==void 0&&(this.dithering=e.dithering),e.alphaToCoverage!==void 0&&(this.alphaToCoverage=e.alphaToCoverage),e.premultipliedAlpha!==void 0&&(this.premultipliedAlpha=e.premultipliedAlpha),e.forceSinglePass!==void 0&&(this.forceSinglePass=e.forceSinglePass),e.allowOverride!==void 0&&(this.allowOverride=e.allowOverride),e.visible!==void 0&&(this.visible=e.visible),e.toneMapped!==void 0&&(this.toneMapped=e.toneMapped),e.userData!==void 0&&(this.userData=e.userData),e.vertexColors!==void 0&&(typeof e.vertexColors=="number"?this.vertexColors=e.vertexColors>0:this.vertexColors=e.vertexColors),e.size!==void 0&&(this.size=e.size),e.sizeAttenuation!==void 0&&(this.sizeAttenuation=e.sizeAttenuation),e.map!==void 0&&(this.map=t[e.map]||null),e.matcap!==void 0&&(this.matcap=t[e.matcap]||null),e.alphaMap!==void 0&&(this.alphaMap=t[e.alphaMap]||null),e.bumpMap!==void 0&&(this.bumpMap=t[e.bumpMap]||null),e.bumpScale!==void 0&&(this.bumpScale=e.bumpScale),e.normalMap!==void 0&&(this.normalMap=t[e.normalMap]||null),e.normalMapType!==void 0&&(this.normalMapType=e.normalMapType),e.normalScale!==void 0){let i=e.normalScale;Array.isArray(i)===!1&&(i=[i,i]),this.normalScale=new it().fromArray(i)}return e.displacementMap!==void 0&&(this.displacementMap=t[e.displacementMap]||null),e.displacementScale!==void 0&&(this.displacementScale=e.displacementScale),e.displacementBias!==void 0&&(this.displacementBias=e.displacementBias),e.roughnessMap!==void 0&&(this.roughnessMap=t[e.roughnessMap]||null),e.metalnessMap!==void 0&&(this.metalnessMap=t[e.metalnessMap]||null),e.emissiveMap!==void 0&&(this.emissiveMap=t[e.emissiveMap]||null),e.emissiveIntensity!==void 0&&(this.emissiveIntensity=e.emissiveIntensity),e.specularMap!==void 0&&(this.specularMap=t[e.specularMap]||null),e.specularIntensityMap!==void 0&&(this.specularIntensityMap=t[e.specularIntensityMap]||null),e.specularColorMap!==void 0&&(this.specularColorMap=t[e.specularColorMap]||null),e.envMap!==void 0&&(this.envMap=t[e.envMap]||null),e.envMapRotation!==void 0&&this.envMapRotation.fromArray(e.envMapRotation),e.envMapIntensity!==void 0&&(this.envMapIntensity=e.envMapIntensity),e.reflectivity!==void 0&&(this.reflectivity=e.reflectivity),e.refractionRatio!==void 0&&(this.refractionRatio=e.refractionRatio),e.lightMap!==void 0&&(this.lightMap=t[e.lightMap]||null),e.lightMapIntensity!==void 0&&(this.lightMapIntensity=e.lightMapIntensity),e.aoMap!==void 0&&(this.aoMap=t[e.aoMap]||null),e.aoMapIntensity!==void 0&&(this.aoMapIntensity=e.aoMapIntensity),e.gradientMap!==void 0&&(this.gradientMap=t[e.gradientMap]||null),e.clearcoatMap!==void 0&&(this.clearcoatMap=t[e.clearcoatMap]||null),e.clearcoatRoughnessMap!==void 0&&(this.clearcoatRoughnessMap=t[e.clearcoatRoughnessMap]||null),e.clearcoatNormalMap!==void 0&&(this.clearcoatNormalMap=t[e.clearcoatNormalMap]||null),e.clearcoatNormalScale!==void 0&&(this.clearcoatNormalScale=new it().fromArray(e.clearcoatNormalScale)),e.diffuseRoughnessMap!==void 0&&(this.diffuseRoughnessMap=t[e.diffuseRoughnessMap]||null),e.iridescenceMap!==void 0&&(this.iridescenceMap=t[e.iridescenceMap]||null),e.iridescenceThicknessMap!==void 0&&(this.iridescenceThicknessMap=t[e.iridescenceThicknessMap]||null),e.transmissionMap!==void 0&&(this.transmissionMap=t[e.transmissionMap]||null),e.thicknessMap!==void 0&&(this.thicknessMap=t[e.thicknessMap]||null),e.anisotropyMap!==void 0&&(this.anisotropyMap=t[e.anisotropyMap]||null),e.sheenColorMap!==void 0&&(this.sheenColorMap=t[e.sheenColorMap]||null),e.sheenRoughnessMap!==void 0&&(this.sheenRoughnessMap=t[e.sheenRoughnessMap]||null),this}clone(){return new this.constructor().copy(this)}copy(e){this.name=e.name,this.blending=e.blending,this.side=e.side,this.vertexColors=e.vertexColors,this.opacity=e.opacity,this.transparent=e.transparent,this.blendSrc=e.blendSrc,this.blendDst=e.blendDst,this.blendEquation=e.blendEquation,this.blendSrcAlpha=e.blendSrcAlpha,this.blendDstAlpha=e.blendDstAlpha,this.blendEquationAlpha=e.blendEquationAlpha,this.blendColor.copy(e.blendColor),this.blendAlpha=e.blendAlpha,this.depthFunc=e.depthFunc,this.depthTest=e.depthTest,this.depthWrite=e.depthWrite,this.stencilWriteMask=e.stencilWriteMask,this.stencilFunc=e.stencilFunc,this.stencilRef=e.stencilRef,this.stencilFuncMask=e.stencilFuncMask,this.stencilFail=e.stencilFail,this.stencilZFail=e.stencilZFail,this.stencilZPass=e.stencilZPass,this.stencilWrite=e.stencilWrite;let t=e.clippingPlanes,i=null;if(t!==null){let r=t.length;i=new Array(r);for(let s=0;s!==r;++s)i[s]=t[s].clone()}return this.clippingPlanes=i,this.clipIntersection=e.clipIntersection,this.clipShadows=e.clipShadows,this.shadowSide=e.shadowSide,this.colorWrite=e.colorWrite,this.precision=e.precision,this.polygonOffset=e.polygonOffset,this.polygonOffsetFactor=e.polygonOffsetFactor,this.polygonOffsetUnits=e.polygonOffsetUnits,this.dithering=e.dithering,this.alphaTest=e.alphaTest,this.alphaHash=e.alphaHash,this.alphaToCoverage=e.alphaToCoverage,this.premultipliedAlpha=e.premultipliedAlpha,this.forceSinglePass=e.forceSinglePass,this.allowOverride=e.allowOverride,this.visible=e.visible,this.toneMapped=e.toneMapped,this.userData=JSON.parse(JSON.stringify(e.userData)),this}dispose(){this.dispatchEvent({type:"dispose"})}set needsUpdate(e){e===!0&&this.version++}};var Vr=new Y,Xp=new Y,vu=new Y,bu=new Y,ds=class{constructor(e=new Y,t=new Y(0,0,-1)){this.origin=e,this.direction=t}set(e,t){return this.origin.copy(e),this.direction.copy(t),this}copy(e){return this.origin.copy(e.origin),this.direction.copy(e.direction),this}at(e,t){return t.copy(this.origin).addScaledVector(this.direction,e)}lookAt(e){return this.direction.copy(e).sub(this.origin).normalize(),this}recast(e){return this.origin.copy(this.at(e,Vr)),this}closestPointToPoint(e,t){t.subVectors(e,this.origin);let i=t.dot(this.direction);return i<0?t.copy(this.origin):t.copy(this.origin).addScaledVector(this.direction,i)}distanceToPoint(e){return Math.sqrt(this.distanceSqToPoint(e))}distanceSqToPoint(e){let t=Vr.subVectors(e,this.origin).dot(this.direction);return t<0?this.origin.distanceToSquared(e):(Vr.copy(this.origin).addScaledVector(this.direction,t),Vr.distanceToSquared(e))}distanceSqToSegment(e,t,i,r){Xp.copy(e).add(t).multiplyScalar(.5),vu.copy(t).sub(e).normalize(),bu.copy(this.origin).sub(Xp);let s=e.distanceTo(t)*.5,o=-this.direction.dot(vu),a=bu.dot(this.direction),l=-bu.dot(vu),c=bu.lengthSq(),u=Math.abs(1-o*o),h,f,d,p;if(u>0)if(h=o*l-a,f=o*a-l,p=s*u,h>=0)if(f>=-p)if(f<=p){let x=1/u;h*=x,f*=x,d=h*(h+o*f+2*a)+f*(o*h+f+2*l)+c}else f=s,h=Math.max(0,-(o*f+a)),d=-h*h+f*(f+2*l)+c;else f=-s,h=Math.max(0,-(o*f+a)),d=-h*h+f*(f+2*l)+c;else f<=-p?(h=Math.max(0,-(-o*s+a)),f=h>0?-s:Math.min(Math.max(-s,-l),s),d=-h*h+f*(f+2*l)+c):f<=p?(h=0,f=Math.min(Math.max(-s,-l),s),d=f*(f+2*l)+c):(h=Math.max(0,-(o*s+a)),f=h>0?s:Math.min(Math.max(-s,-l),s),d=-h*h+f*(f+2*l)+c);else f=o>0?-s:s,h=Math.max(0,-(o*f+a)),d=-h*h+f*(f+2*l)+c;return i&&i.copy(this.origin).addScaledVector(this.direction,h),r&&r.copy(Xp).addScaledVector(vu,f),d}intersectSphere(e,t){if(e.radius<0)return null;Vr.subVectors(e.center,this.origin);let i=Vr.dot(this.direction),r=Vr.dot(Vr)-i*i,s=e.radius*e.radius;if(r>s)return null;let o=Math.sqrt(s-r),a=i-o,l=i+o;return l<0?null:a<0?this.at(l,t):this.at(a,t)}intersectsSphere(e){return e.radius<0?!1:this.distanceSqToPoint(e.center)<=e.radius*e.radius}distanceToPlane(e){let t=e.normal.dot(this.direction);if(t===0)return e.distanceToPoint(this.origin)===0?0:null;let i=-(this.origin.dot(e.normal)+e.constant)/t;return i>=0?i:null}intersectPlane(e,t){let i=this.distanceToPlane(e);return i===null?null:this.at(i,t)}intersectsPlane(e){let t=e.distanceToPoint(this.origin);return t===0||e.normal.dot(this.direction)*t<0}intersectBox(e,t){let i,r,s,o,a,l,c=1/this.direction.x,u=1/this.direction.y,h=1/this.direction.z,f=this.origin;return c>=0?(i=(e.min.x-f.x)*c,r=(e.max.x-f.x)*c):(i=(e.max.x-f.x)*c,r=(e.min.x-f.x)*c),u>=0?(s=(e.min.y-f.y)*u,o=(e.max.y-f.y)*u):(s=(e.max.y-f.y)*u,o=(e.min.y-f.y)*u),i>o||s>r||((s>i||isNaN(i))&&(i=s),(o<r||isNaN(r))&&(r=o),h>=0?(a=(e.min.z-f.z)*h,l=(e.max.z-f.z)*h):(a=(e.max.z-f.z)*h,l=(e.min.z-f.z)*h),i>l||a>r)||((a>i||i!==i)&&(i=a),(l<r||r!==r)&&(r=l),r<0)?null:this.at(i>=0?i:r,t)}intersectsBox(e){return this.intersectBox(e,Vr)!==null}intersectTriangle(e,t,i,r,s){let o=this.origin,a=this.direction,l=a.x,c=a.y,u=a.z,h=e.x-o.x,f=e.y-o.y,d=e.z-o.z,p=t.x-o.x,x=t.y-o.y,m=t.z-o.z,g=i.x-o.x,v=i.y-o.y,T=i.z-o.z,M=Math.abs(l),R=Math.abs(c),w=Math.abs(u),y,A,k,D,L,H,z,N,F,Z,V,le;if(M>=R&&M>=w?(k=l,H=h,F=p,le=g,l>=0?(y=c,A=u,D=f,L=d,z=x,N=m,Z=v,V=T):(y=u,A=c,D=d,L=f,z=m,N=x,Z=T,V=v)):R>=w?(k=c,H=f,F=x,le=v,c>=0?(y=u,A=l,D=d,L=h,z=m,N=p,Z=T,V=g):(y=l,A=u,D=h,L=d,z=p,N=m,Z=g,V=T)):(k=u,H=d,F=m,le=T,u>=0?(y=l,A=c,D=h,L=f,z=p,N=x,Z=g,V=v):(y=c,A=l,D=f,L=h,z=x,N=p,Z=v,V=g)),k===0)return null;let q=y/k,Q=A/k,ie=1/k,fe=D-q*H,he=L-Q*H,ee=z-q*F,ge=N-Q*F,ye=Z-q*le,xe=V-Q*le,_e=ye*ge-xe*ee,ze=fe*xe-he*ye,$e=ee*he-ge*fe;if(r){if(_e<0||ze<0||$e<0)return null}else if((_e<0||ze<0||$e<0)&&(_e>0||ze>0||$e>0))return null;let Fe=_e+ze+$e;if(Fe===0)return null;let st=ie*(_e*H+ze*F+$e*le);return(Fe>0?st<0:st>0)?null:this.at(st/Fe,s)}applyMatrix4(e){return this.origin.applyMatrix4(e),this.direction.transformDirection(e),this}equals(e){return e.origin.equals(this.origin)&&e.direction.equals(this.direction)}clone(){return new this.constructor().copy(this)}},ju=class extends xr{constructor(e){super(),this.isMeshBasicMaterial=!0,this.type="MeshBasicMaterial",this.color=new ft(16777215),this.map=null,this.lightMap=null,this.lightMapIntensity=1,this.aoMap=null,this.aoMapIntensity=1,this.specularMap=null,this.alphaMap=null,this.envMap=null,this.envMapRotation=new Hr,this.combine=_h,this.reflectivity=1,this.refractionRatio=.98,this.wireframe=!1,this.wireframeLinewidth=1,this.wireframeLinecap="round",this.wireframeLinejoin="round",this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.lightMap=e.lightMap,this.lightMapIntensity=e.lightMapIntensity,this.aoMap=e.aoMap,this.aoMapIntensity=e.aoMapIntensity,this.specularMap=e.specularMap,this.alphaMap=e.alphaMap,this.envMap=e.envMap,this.envMapRotation.copy(e.envMapRotation),this.combine=e.combine,this.reflectivity=e.reflectivity,this.refractionRatio=e.refractionRatio,this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this.wireframeLinecap=e.wireframeLinecap,this.wireframeLinejoin=e.wireframeLinejoin,this.fog=e.fog,this}},xv=new Ht,Hs=new ds,Su=new fs,vv=new Y,Mu=new Y,Eu=new Y,wu=new Y,Yp=new Y,Au=new Y,bv=new Y,Tu=new Y,Ti=class extends zn{constructor(e=new ci,t=new ju){super(),this.isMesh=!0,this.type="Mesh",this.geometry=e,this.material=t,this.morphTargetDictionary=void 0,this.morphTargetInfluences=void 0,this.count=1,this.updateMorphTargets()}copy(e,t){return super.copy(e,t),e.morphTargetInfluences!==void 0?this.morphTargetInfluences=e.morphTargetInfluences.slice():this.morphTargetInfluences=void 0,e.morphTargetDictionary!==void 0?this.morphTargetDictionary=Object.assign({},e.morphTargetDictionary):this.morphTargetDictionary=void 0,this.material=Array.isArray(e.material)?e.material.slice():e.material,this.geometry=e.geometry,this}updateMorphTargets(){let t=this.geometry.morphAttributes,i=Object.keys(t);if(i.length>0){let r=t[i[0]];if(r!==void 0){this.morphTargetInfluences=[],this.morphTargetDictionary={};for(let s=0,o=r.length;s<o;s++){let a=r[s].name||String(s);this.morphTargetInfluences.push(0),this.morphTargetDictionary[a]=s}}}}getVertexPosition(e,t){let i=this.geometry,r=i.attributes.position,s=i.morphAttributes.position,o=i.morphTargetsRelative;t.fromBufferAttribute(r,e);let a=this.morphTargetInfluences;if(s&&a){Au.set(0,0,0);for(let l=0,c=s.length;l<c;l++){let u=a[l],h=s[l];u!==0&&(Yp.fromBufferAttribute(h,e),o?Au.addScaledVector(Yp,u):Au.addScaledVector(Yp.sub(t),u))}t.add(Au)}return t}intersectsFrustum(e){return e.intersectsObject(this)}raycast(e,t){let i=this.geometry,r=this.material,s=this.matrixWorld;r!==void 0&&(i.boundingSphere===null&&i.computeBoundingSphere(),Su.copy(i.boundingSphere),Su.applyMatrix4(s),Hs.copy(e.ray).recast(e.near),!(Su.containsPoint(Hs.origin)===!1&&(Hs.intersectSphere(Su,vv)===null||Hs.origin.distanceToSquared(vv)>(e.far-e.near)**2))&&(xv.copy(s).invert(),Hs.copy(e.ray).applyMatrix4(xv),!(i.boundingBox!==null&&Hs.intersectsBox(i.boundingBox)===!1)&&this._computeIntersections(e,t,Hs)))}_computeIntersections(e,t,i){let r,s=this.geometry,o=this.material,a=s.index,l=s.attributes.position,c=s.attributes.uv,u=s.attributes.uv1,h=s.attributes.normal,f=s.groups,d=s.drawRange;if(a!==null)if(Array.isArray(o))for(let p=0,x=f.length;p<x;p++){let m=f[p],g=o[m.materialIndex],v=Math.max(m.start,d.start),T=Math.min(a.count,Math.min(m.start+m.count,d.start+d.count));for(let M=v,R=T;M<R;M+=3){let w=a.getX(M),y=a.getX(M+1),A=a.getX(M+2);r=Ru(this,g,e,i,c,u,h,w,y,A),r&&(r.faceIndex=Math.floor(M/3),r.face.materialIndex=m.materialIndex,t.push(r))}}else{let p=Math.max(0,d.start),x=Math.min(a.count,d.start+d.count);for(let m=p,g=x;m<g;m+=3){let v=a.getX(m),T=a.getX(m+1),M=a.getX(m+2);r=Ru(this,o,e,i,c,u,h,v,T,M),r&&(r.faceIndex=Math.floor(m/3),t.push(r))}}else if(l!==void 0)if(Array.isArray(o))for(let p=0,x=f.length;p<x;p++){let m=f[p],g=o[m.materialIndex],v=Math.max(m.start,d.start),T=Math.min(l.count,Math.min(m.start+m.count,d.start+d.count));for(let M=v,R=T;M<R;M+=3){let w=M,y=M+1,A=M+2;r=Ru(this,g,e,i,c,u,h,w,y,A),r&&(r.faceIndex=Math.floor(M/3),r.face.materialIndex=m.materialIndex,t.push(r))}}else{let p=Math.max(0,d.start),x=Math.min(l.count,d.start+d.count);for(let m=p,g=x;m<g;m+=3){let v=m,T=m+1,M=m+2;r=Ru(this,o,e,i,c,u,h,v,T,M),r&&(r.faceIndex=Math.floor(m/3),t.push(r))}}}};function rT(n,e,t,i,r,s,o,a){let l;if(e.side===ui?l=i.intersectTriangle(o,s,r,!0,a):l=i.intersectTriangle(r,s,o,e.side===vs,a),l===null)return null;Tu.copy(a),Tu.applyMatrix4(n.matrixWorld);let c=t.ray.origin.distanceTo(Tu);return c<t.near||c>t.far?null:{distance:c,point:Tu.clone(),object:n}}function Ru(n,e,t,i,r,s,o,a,l,c){n.getVertexPosition(a,Mu),n.getVertexPosition(l,Eu),n.getVertexPosition(c,wu);let u=rT(n,e,t,i,Mu,Eu,wu,bv);if(u){let h=new Y;hs.getBarycoord(bv,Mu,Eu,wu,h),r&&(u.uv=hs.getInterpolatedAttribute(r,a,l,c,h,new it)),s&&(u.uv1=hs.getInterpolatedAttribute(s,a,l,c,h,new it)),o&&(u.normal=hs.getInterpolatedAttribute(o,a,l,c,h,new Y),u.normal.dot(i.direction)>0&&u.normal.multiplyScalar(-1));let f={a,b:l,c,normal:new Y,materialIndex:0};hs.getNormal(Mu,Eu,wu,f.normal),u.face=f,u.barycoord=h}return u}var Qu=class extends fi{constructor(e=null,t=1,i=1,r,s,o,a,l,c=kn,u=kn,h,f){super(null,o,a,l,c,u,r,s,h,f),this.isDataTexture=!0,this.image={data:e,width:t,height:i},this.generateMipmaps=!1,this.flipY=!1,this.unpackAlignment=1}};var Ws=new fs,sT=new it(.5,.5),Iu=new Y,ps=class{constructor(e=new oi,t=new oi,i=new oi,r=new oi,s=new oi,o=new oi){this.planes=[e,t,i,r,s,o]}set(e,t,i,r,s,o){let a=this.planes;return a[0].copy(e),a[1].copy(t),a[2].copy(i),a[3].copy(r),a[4].copy(s),a[5].copy(o),this}copy(e){let t=this.planes;for(let i=0;i<6;i++)t[i].copy(e.planes[i]);return this}setFromProjectionMatrix(e,t=Oi,i=!1){let r=this.planes,s=e.elements,o=s[0],a=s[1],l=s[2],c=s[3],u=s[4],h=s[5],f=s[6],d=s[7],p=s[8],x=s[9],m=s[10],g=s[11],v=s[12],T=s[13],M=s[14],R=s[15];if(r[0].setComponents(c-o,d-u,g-p,R-v).normalize(),r[1].setComponents(c+o,d+u,g+p,R+v).normalize(),r[2].setComponents(c+a,d+h,g+x,R+T).normalize(),r[3].setComponents(c-a,d-h,g-x,R-T).normalize(),i)r[4].setComponents(l,f,m,M).normalize(),r[5].setComponents(c-l,d-f,g-m,R-M).normalize();else if(r[4].setComponents(c-l,d-f,g-m,R-M).normalize(),t===Oi)r[5].setComponents(c+l,d+f,g+m,R+M).normalize();else if(t===$o)r[5].setComponents(l,f,m,M).normalize();else throw new Error("THREE.Frustum.setFromProjectionMatrix(): Invalid coordinate system: "+t);return this}intersectsObject(e){if(e.boundingSphere!==void 0)e.boundingSphere===null&&e.computeBoundingSphere(),Ws.copy(e.boundingSphere).applyMatrix4(e.matrixWorld);else{let t=e.geometry;t.boundingSphere===null&&t.computeBoundingSphere(),Ws.copy(t.boundingSphere).applyMatrix4(e.matrixWorld)}return this.intersectsSphere(Ws)}intersectsSprite(e){Ws.center.set(0,0,0);let t=sT.distanceTo(e.center);return Ws.radius=.7071067811865476+t,Ws.applyMatrix4(e.matrixWorld),this.intersectsSphere(Ws)}intersectsSphere(e){let t=this.planes,i=e.center,r=-e.radius;for(let s=0;s<6;s++)if(t[s].distanceToPoint(i)<r)return!1;return!0}intersectsBox(e){let t=this.planes;for(let i=0;i<6;i++){let r=t[i];if(Iu.x=r.normal.x>0?e.max.x:e.min.x,Iu.y=r.normal.y>0?e.max.y:e.min.y,Iu.z=r.normal.z>0?e.max.z:e.min.z,r.distanceToPoint(Iu)<0)return!1}return!0}containsPoint(e){let t=this.planes;for(let i=0;i<6;i++)if(t[i].distanceToPoint(e)<0)return!1;return!0}clone(){return new this.constructor().copy(this)}},Sv=new Ht,eh=class n{constructor(){this.coordinateSystem=Oi,this._frustums=[],this._count=0}setFromArrayCamera(e){let t=e.cameras,i=this._frustums;for(let r=0;r<t.length;r++){let s=t[r];Sv.multiplyMatrices(s.projectionMatrix,s.matrixWorldInverse),i[r]===void 0&&(i[r]=new ps),i[r].setFromProjectionMatrix(Sv,s.coordinateSystem,s.reversedDepth)}return this._count=t.length,this}getFrustum(e){return this._frustums[e]}intersectsObject(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsObject(e))return!0;return!1}intersectsSprite(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsSprite(e))return!0;return!1}intersectsSphere(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsSphere(e))return!0;return!1}intersectsBox(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].intersectsBox(e))return!0;return!1}containsPoint(e){let t=this._frustums;for(let i=0;i<this._count;i++)if(t[i].containsPoint(e))return!0;return!1}copy(e){this.coordinateSystem=e.coordinateSystem;let t=this._frustums,i=e._frustums;for(let r=0;r<e._count;r++)t[r]===void 0&&(t[r]=new ps),t[r].copy(i[r]);return this._count=e._count,this}clone(){return new n().copy(this)}};var ea=class extends xr{constructor(e){super(),this.isLineBasicMaterial=!0,this.type="LineBasicMaterial",this.color=new ft(16777215),this.map=null,this.linewidth=1,this.linecap="round",this.linejoin="round",this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.linewidth=e.linewidth,this.linecap=e.linecap,this.linejoin=e.linejoin,this.fog=e.fog,this}},th=new Y,nh=new Y,Mv=new Ht,ll=new ds,Cu=new fs,Zp=new Y,Ev=new Y,bl=class extends zn{constructor(e=new ci,t=new ea){super(),this.isLine=!0,this.type="Line",this.geometry=e,this.material=t,this.morphTargetDictionary=void 0,this.morphTargetInfluences=void 0,this.updateMorphTargets()}copy(e,t){return super.copy(e,t),e.morphTargetInfluences!==void 0?this.morphTargetInfluences=e.morphTargetInfluences.slice():this.morphTargetInfluences=void 0,e.morphTargetDictionary!==void 0?this.morphTargetDictionary=Object.assign({},e.morphTargetDictionary):this.morphTargetDictionary=void 0,this.material=Array.isArray(e.material)?e.material.slice():e.material,this.geometry=e.geometry,this}computeLineDistances(){let e=this.geometry;if(e.index===null){let t=e.attributes.position,i=[0];for(let r=1,s=t.count;r<s;r++)th.fromBufferAttribute(t,r-1),nh.fromBufferAttribute(t,r),i[r]=i[r-1],i[r]+=th.distanceTo(nh);e.setAttribute("lineDistance",new qn(i,1))}else Ke("Line.computeLineDistances(): Computation only possible with non-indexed BufferGeometry.");return this}intersectsFrustum(e){return e.intersectsObject(this)}raycast(e,t){let i=this.geometry,r=this.matrixWorld,s=e.params.Line.threshold,o=i.drawRange;if(i.boundingSphere===null&&i.computeBoundingSphere(),Cu.copy(i.boundingSphere),Cu.applyMatrix4(r),Cu.radius+=s,e.ray.intersectsSphere(Cu)===!1)return;Mv.copy(r).invert(),ll.copy(e.ray).applyMatrix4(Mv);let a=s/((this.scale.x+this.scale.y+this.scale.z)/3),l=a*a,c=this.isLineSegments?2:1,u=i.index,f=i.attributes.position;if(u!==null){let d=Math.max(0,o.start),p=Math.min(u.count,o.start+o.count);for(let x=d,m=p-1;x<m;x+=c){let g=u.getX(x),v=u.getX(x+1),T=Nu(this,e,ll,l,g,v,x);T&&t.push(T)}if(this.isLineLoop){let x=u.getX(p-1),m=u.getX(d),g=Nu(this,e,ll,l,x,m,p-1);g&&t.push(g)}}else{let d=Math.max(0,o.start),p=Math.min(f.count,o.start+o.count);for(let x=d,m=p-1;x<m;x+=c){let g=Nu(this,e,ll,l,x,x+1,x);g&&t.push(g)}if(this.isLineLoop){let x=Nu(this,e,ll,l,p-1,d,p-1);x&&t.push(x)}}}updateMorphTargets(){let t=this.geometry.morphAttributes,i=Object.keys(t);if(i.length>0){let r=t[i[0]];if(r!==void 0){this.morphTargetInfluences=[],this.morphTargetDictionary={};for(let s=0,o=r.length;s<o;s++){let a=r[s].name||String(s);this.morphTargetInfluences.push(0),this.morphTargetDictionary[a]=s}}}}};function Nu(n,e,t,i,r,s,o){let a=n.geometry.attributes.position;if(th.fromBufferAttribute(a,r),nh.fromBufferAttribute(a,s),t.distanceSqToSegment(th,nh,Zp,Ev)>i)return;Zp.applyMatrix4(n.matrixWorld);let c=e.ray.origin.distanceTo(Zp);if(!(c<e.near||c>e.far))return{distance:c,point:Ev.clone().applyMatrix4(n.matrixWorld),index:o,face:null,faceIndex:null,barycoord:null,object:n}}var ta=class extends xr{constructor(e){super(),this.isPointsMaterial=!0,this.type="PointsMaterial",this.color=new ft(16777215),this.map=null,this.alphaMap=null,this.size=1,this.sizeAttenuation=!0,this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.alphaMap=e.alphaMap,this.size=e.size,this.sizeAttenuation=e.sizeAttenuation,this.fog=e.fog,this}},wv=new Ht,Qp=new ds,Pu=new fs,Lu=new Y,Sl=class extends zn{constructor(e=new ci,t=new ta){super(),this.isPoints=!0,this.type="Points",this.geometry=e,this.material=t,this.morphTargetDictionary=void 0,this.morphTargetInfluences=void 0,this.updateMorphTargets()}copy(e,t){return super.copy(e,t),e.morphTargetInfluences!==void 0?this.morphTargetInfluences=e.morphTargetInfluences.slice():this.morphTargetInfluences=void 0,e.morphTargetDictionary!==void 0?this.morphTargetDictionary=Object.assign({},e.morphTargetDictionary):this.morphTargetDictionary=void 0,this.material=Array.isArray(e.material)?e.material.slice():e.material,this.geometry=e.geometry,this}intersectsFrustum(e){return e.intersectsObject(this)}raycast(e,t){let i=this.geometry,r=this.matrixWorld,s=e.params.Points.threshold,o=i.drawRange;if(i.boundingSphere===null&&i.computeBoundingSphere(),Pu.copy(i.boundingSphere),Pu.applyMatrix4(r),Pu.radius+=s,e.ray.intersectsSphere(Pu)===!1)return;wv.copy(r).invert(),Qp.copy(e.ray).applyMatrix4(wv);let a=s/((this.scale.x+this.scale.y+this.scale.z)/3),l=a*a,c=i.index,h=i.attributes.position;if(c!==null){let f=Math.max(0,o.start),d=Math.min(c.count,o.start+o.count);for(let p=f,x=d;p<x;p++){let m=c.getX(p);Lu.fromBufferAttribute(h,m),Av(Lu,m,l,r,e,t,this)}}else{let f=Math.max(0,o.start),d=Math.min(h.count,o.start+o.count);for(let p=f,x=d;p<x;p++)Lu.fromBufferAttribute(h,p),Av(Lu,p,l,r,e,t,this)}}updateMorphTargets(){let t=this.geometry.morphAttributes,i=Object.keys(t);if(i.length>0){let r=t[i[0]];if(r!==void 0){this.morphTargetInfluences=[],this.morphTargetDictionary={};for(let s=0,o=r.length;s<o;s++){let a=r[s].name||String(s);this.morphTargetInfluences.push(0),this.morphTargetDictionary[a]=s}}}}};function Av(n,e,t,i,r,s,o){let a=Qp.distanceSqToPoint(n);if(a<t){let l=new Y;Qp.closestPointToPoint(n,l),l.applyMatrix4(i);let c=r.ray.origin.distanceTo(l);if(c<r.near||c>r.far)return;s.push({distance:c,distanceToRay:Math.sqrt(a),point:l,index:e,face:null,faceIndex:null,barycoord:null,object:o})}}var Ml=class extends fi{constructor(e=[],t=Ks,i,r,s,o,a,l,c,u){super(e,t,i,r,s,o,a,l,c,u),this.isCubeTexture=!0,this.flipY=!1}get images(){return this.image}set images(e){this.image=e}};var Wr=class extends fi{constructor(e,t,i=Qi,r,s,o,a=kn,l=kn,c,u=zr,h=1){if(u!==zr&&u!==Yr)throw new Error("THREE.DepthTexture: format must be either THREE.DepthFormat or THREE.DepthStencilFormat");let f={width:e,height:t,depth:h};super(f,r,s,o,a,l,u,i,c),this.isDepthTexture=!0,this.flipY=!1,this.generateMipmaps=!1,this.compareFunction=null}copy(e){return super.copy(e),this.source=new jo(Object.assign({},e.image)),this.compareFunction=e.compareFunction,this}toJSON(e){let t=super.toJSON(e);return t.compareFunction=this.compareFunction,t}},El=class extends Wr{constructor(e,t=Qi,i=Ks,r,s,o=kn,a=kn,l,c=zr){let u={width:e,height:e,depth:1},h=[u,u,u,u,u,u];super(e,e,t,i,r,s,o,a,l,c),this.image=h,this.isCubeDepthTexture=!0,this.isCubeTexture=!0}get images(){return this.image}set images(e){this.image=e}},wl=class extends fi{constructor(e=null){super(),this.sourceTexture=e,this.isExternalTexture=!0}copy(e){return super.copy(e),this.sourceTexture=e.sourceTexture,this}},na=class n extends ci{constructor(e=1,t=1,i=1,r=1,s=1,o=1){super(),this.type="BoxGeometry",this.parameters={width:e,height:t,depth:i,widthSegments:r,heightSegments:s,depthSegments:o};let a=this;r=Math.floor(r),s=Math.floor(s),o=Math.floor(o);let l=[],c=[],u=[],h=[],f=0,d=0;p("z","y","x",-1,-1,i,t,e,o,s,0),p("z","y","x",1,-1,i,t,-e,o,s,1),p("x","z","y",1,1,e,i,t,r,o,2),p("x","z","y",1,-1,e,i,-t,r,o,3),p("x","y","z",1,-1,e,t,i,r,s,4),p("x","y","z",-1,-1,e,t,-i,r,s,5),this.setIndex(l),this.setAttribute("position",new qn(c,3)),this.setAttribute("normal",new qn(u,3)),this.setAttribute("uv",new qn(h,2));function p(x,m,g,v,T,M,R,w,y,A,k){let D=M/y,L=R/A,H=M/2,z=R/2,N=w/2,F=y+1,Z=A+1,V=0,le=0,q=new Y;for(let Q=0;Q<Z;Q++){let ie=Q*L-z;for(let fe=0;fe<F;fe++){let he=fe*D-H;q[x]=he*v,q[m]=ie*T,q[g]=N,c.push(q.x,q.y,q.z),q[x]=0,q[m]=0,q[g]=w>0?1:-1,u.push(q.x,q.y,q.z),h.push(fe/y),h.push(1-Q/A),V+=1}}for(let Q=0;Q<A;Q++)for(let ie=0;ie<y;ie++){let fe=f+ie+F*Q,he=f+ie+F*(Q+1),ee=f+(ie+1)+F*(Q+1),ge=f+(ie+1)+F*Q;l.push(fe,he,ge),l.push(he,ee,ge),le+=6}a.addGroup(d,le,k),d+=le,f+=V}}copy(e){return super.copy(e),this.parameters=Object.assign({},e.parameters),this}static fromJSON(e){return new n(e.width,e.height,e.depth,e.widthSegments,e.heightSegments,e.depthSegments)}};var Al=class n extends ci{constructor(e=1,t=1,i=1,r=1){super(),this.type="PlaneGeometry",this.parameters={width:e,height:t,widthSegments:i,heightSegments:r};let s=e/2,o=t/2,a=Math.floor(i),l=Math.floor(r),c=a+1,u=l+1,h=e/a,f=t/l,d=[],p=[],x=[],m=[];for(let g=0;g<u;g++){let v=g*f-o;for(let T=0;T<c;T++){let M=T*h-s;p.push(M,-v,0),x.push(0,0,1),m.push(T/a),m.push(1-g/l)}}for(let g=0;g<l;g++)for(let v=0;v<a;v++){let T=v+c*g,M=v+c*(g+1),R=v+1+c*(g+1),w=v+1+c*g;d.push(T,M,w),d.push(M,R,w)}this.setIndex(d),this.setAttribute("position",new qn(p,3)),this.setAttribute("normal",new qn(x,3)),this.setAttribute("uv",new qn(m,2))}copy(e){return super.copy(e),this.parameters=Object.assign({},e.parameters),this}static fromJSON(e){return new n(e.width,e.height,e.widthSegments,e.heightSegments)}};var Tl=class n extends ci{constructor(e=1,t=32,i=16,r=0,s=Math.PI*2,o=0,a=Math.PI){super(),this.type="SphereGeometry",this.parameters={radius:e,widthSegments:t,heightSegments:i,phiStart:r,phiLength:s,thetaStart:o,thetaLength:a},t=Math.max(3,Math.floor(t)),i=Math.max(2,Math.floor(i));let l=Math.min(o+a,Math.PI),c=0,u=[],h=new Y,f=new Y,d=[],p=[],x=[],m=[];for(let g=0;g<=i;g++){let v=[],T=g/i,M=o+T*a,R=e*Math.cos(M),w=Math.sqrt(e*e-R*R),y=0;g===0&&o===0?y=.5/t:g===i&&l===Math.PI&&(y=-.5/t);for(let A=0;A<=t;A++){let k=A/t,D=r+k*s;h.x=-w*Math.cos(D),h.y=R,h.z=w*Math.sin(D),p.push(h.x,h.y,h.z),f.copy(h).normalize(),x.push(f.x,f.y,f.z),m.push(k+y,1-T),v.push(c++)}u.push(v)}for(let g=0;g<i;g++)for(let v=0;v<t;v++){let T=u[g][v+1],M=u[g][v],R=u[g+1][v],w=u[g+1][v+1];(g!==0||o>0)&&d.push(T,M,w),(g!==i-1||l<Math.PI)&&d.push(M,R,w)}this.setIndex(d),this.setAttribute("position",new qn(p,3)),this.setAttribute("normal",new qn(x,3)),this.setAttribute("uv",new qn(m,2))}copy(e){return super.copy(e),this.parameters=Object.assign({},e.parameters),this}static fromJSON(e){return new n(e.radius,e.widthSegments,e.heightSegments,e.phiStart,e.phiLength,e.thetaStart,e.thetaLength)}};function qs(n){let e={};for(let t in n){e[t]={};for(let i in n[t]){let r=n[t][i];if(Tv(r))r.isRenderTargetTexture?(Ke("UniformsUtils: Textures of render targets cannot be cloned via cloneUniforms() or mergeUniforms()."),e[t][i]=null):e[t][i]=r.clone();else if(Array.isArray(r))if(Tv(r[0])){let s=[];for(let o=0,a=r.length;o<a;o++)s[o]=r[o].clone();e[t][i]=s}else e[t][i]=r.slice();else e[t][i]=r}}return e}function Jn(n){let e={};for(let t=0;t<n.length;t++){let i=qs(n[t]);for(let r in i)e[r]=i[r]}return e}function Tv(n){return n&&(n.isColor||n.isMatrix3||n.isMatrix4||n.isVector2||n.isVector3||n.isVector4||n.isTexture||n.isQuaternion)}function oT(n){let e=[];for(let t=0;t<n.length;t++)e.push(n[t].clone());return e}function Lm(n){let e=n.getRenderTarget();return e===null?n.outputColorSpace:e.isXRRenderTarget===!0?e.texture.colorSpace:vt.workingColorSpace}var vb={clone:qs,merge:Jn},aT=`void main() {
	gl_Position = projectionMatrix * modelViewMatrix * vec4( position, 1.0 );
}`,lT=`void main() {
	gl_FragColor = vec4( 1.0, 0.0, 0.0, 1.0 );
}`,vr=class extends xr{constructor(e){super(),this.isShaderMaterial=!0,this.type="ShaderMaterial",this.defines={},this.uniforms={},this.uniformsGroups=[],this.vertexShader=aT,this.fragmentShader=lT,this.linewidth=1,this.wireframe=!1,this.wireframeLinewidth=1,this.fog=!1,this.lights=!1,this.clipping=!1,this.forceSinglePass=!0,this.extensions={clipCullDistance:!1,multiDraw:!1},this.defaultAttributeValues={color:[1,1,1],uv:[0,0],uv1:[0,0]},this.index0AttributeName=void 0,this.uniformsNeedUpdate=!1,this.glslVersion=null,e!==void 0&&this.setValues(e)}copy(e){return super.copy(e),this.fragmentShader=e.fragmentShader,this.vertexShader=e.vertexShader,this.uniforms=qs(e.uniforms),this.uniformsGroups=oT(e.uniformsGroups),this.defines=Object.assign({},e.defines),this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this.fog=e.fog,this.lights=e.lights,this.clipping=e.clipping,this.extensions=Object.assign({},e.extensions),this.glslVersion=e.glslVersion,this.defaultAttributeValues=Object.assign({},e.defaultAttributeValues),this.index0AttributeName=e.index0AttributeName,this.uniformsNeedUpdate=e.uniformsNeedUpdate,this}toJSON(e){let t=super.toJSON(e);t.glslVersion=this.glslVersion,t.uniforms={};for(let r in this.uniforms){let o=this.uniforms[r].value;o&&o.isTexture?t.uniforms[r]={type:"t",value:o.toJSON(e).uuid}:o&&o.isColor?t.uniforms[r]={type:"c",value:o.getHex()}:o&&o.isVector2?t.uniforms[r]={type:"v2",value:o.toArray()}:o&&o.isVector3?t.uniforms[r]={type:"v3",value:o.toArray()}:o&&o.isVector4?t.uniforms[r]={type:"v4",value:o.toArray()}:o&&o.isMatrix3?t.uniforms[r]={type:"m3",value:o.toArray()}:o&&o.isMatrix4?t.uniforms[r]={type:"m4",value:o.toArray()}:t.uniforms[r]={value:o}}Object.keys(this.defines).length>0&&(t.defines=this.defines),t.vertexShader=this.vertexShader,t.fragmentShader=this.fragmentShader,t.lights=this.lights,t.clipping=this.clipping;let i={};for(let r in this.extensions)this.extensions[r]===!0&&(i[r]=!0);return Object.keys(i).length>0&&(t.extensions=i),t}fromJSON(e,t){if(super.fromJSON(e,t),e.uniforms!==void 0)for(let i in e.uniforms){let r=e.uniforms[i];switch(this.uniforms[i]={},r.type){case"t":this.uniforms[i].value=t[r.value]||null;break;case"c":this.uniforms[i].value=new ft().setHex(r.value);break;case"v2":this.uniforms[i].value=new it().fromArray(r.value);break;case"v3":this.uniforms[i].value=new Y().fromArray(r.value);break;case"v4":this.uniforms[i].value=new jt().fromArray(r.value);break;case"m3":this.uniforms[i].value=new rt().fromArray(r.value);break;case"m4":this.uniforms[i].value=new Ht().fromArray(r.value);break;default:this.uniforms[i].value=r.value}}if(e.defines!==void 0&&(this.defines=e.defines),e.vertexShader!==void 0&&(this.vertexShader=e.vertexShader),e.fragmentShader!==void 0&&(this.fragmentShader=e.fragmentShader),e.glslVersion!==void 0&&(this.glslVersion=e.glslVersion),e.extensions!==void 0)for(let i in e.extensions)this.extensions[i]=e.extensions[i];return e.lights!==void 0&&(this.lights=e.lights),e.clipping!==void 0&&(this.clipping=e.clipping),this}},ih=class extends vr{constructor(e){super(e),this.isRawShaderMaterial=!0,this.type="RawShaderMaterial"}};var ia=class extends xr{constructor(e){super(),this.isMeshLambertMaterial=!0,this.type="MeshLambertMaterial",this.color=new ft(16777215),this.map=null,this.lightMap=null,this.lightMapIntensity=1,this.aoMap=null,this.aoMapIntensity=1,this.emissive=new ft(0),this.emissiveIntensity=1,this.emissiveMap=null,this.bumpMap=null,this.bumpScale=1,this.normalMap=null,this.normalMapType=sf,this.normalScale=new it(1,1),this.displacementMap=null,this.displacementScale=1,this.displacementBias=0,this.specularMap=null,this.alphaMap=null,this.envMap=null,this.envMapRotation=new Hr,this.combine=_h,this.reflectivity=1,this.envMapIntensity=1,this.refractionRatio=.98,this.wireframe=!1,this.wireframeLinewidth=1,this.wireframeLinecap="round",this.wireframeLinejoin="round",this.flatShading=!1,this.fog=!0,this.setValues(e)}copy(e){return super.copy(e),this.color.copy(e.color),this.map=e.map,this.lightMap=e.lightMap,this.lightMapIntensity=e.lightMapIntensity,this.aoMap=e.aoMap,this.aoMapIntensity=e.aoMapIntensity,this.emissive.copy(e.emissive),this.emissiveMap=e.emissiveMap,this.emissiveIntensity=e.emissiveIntensity,this.bumpMap=e.bumpMap,this.bumpScale=e.bumpScale,this.normalMap=e.normalMap,this.normalMapType=e.normalMapType,this.normalScale.copy(e.normalScale),this.displacementMap=e.displacementMap,this.displacementScale=e.displacementScale,this.displacementBias=e.displacementBias,this.specularMap=e.specularMap,this.alphaMap=e.alphaMap,this.envMap=e.envMap,this.envMapRotation.copy(e.envMapRotation),this.combine=e.combine,this.reflectivity=e.reflectivity,this.envMapIntensity=e.envMapIntensity,this.refractionRatio=e.refractionRatio,this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this.wireframeLinecap=e.wireframeLinecap,this.wireframeLinejoin=e.wireframeLinejoin,this.flatShading=e.flatShading,this.fog=e.fog,this}},rh=class extends xr{constructor(e){super(),this.isMeshDepthMaterial=!0,this.type="MeshDepthMaterial",this.depthPacking=rb,this.map=null,this.alphaMap=null,this.displacementMap=null,this.displacementScale=1,this.displacementBias=0,this.wireframe=!1,this.wireframeLinewidth=1,this.setValues(e)}copy(e){return super.copy(e),this.depthPacking=e.depthPacking,this.map=e.map,this.alphaMap=e.alphaMap,this.displacementMap=e.displacementMap,this.displacementScale=e.displacementScale,this.displacementBias=e.displacementBias,this.wireframe=e.wireframe,this.wireframeLinewidth=e.wireframeLinewidth,this}},sh=class extends xr{constructor(e){super(),this.isMeshDistanceMaterial=!0,this.type="MeshDistanceMaterial",this.map=null,this.alphaMap=null,this.displacementMap=null,this.displacementScale=1,this.displacementBias=0,this.setValues(e)}copy(e){return super.copy(e),this.map=e.map,this.alphaMap=e.alphaMap,this.displacementMap=e.displacementMap,this.displacementScale=e.displacementScale,this.displacementBias=e.displacementBias,this}};function Wo(n,e){return!n||n.constructor===e?n:typeof e.BYTES_PER_ELEMENT=="number"?new e(n):Array.prototype.slice.call(n)}function Du(n){return n!==void 0&&n.inTangents!==void 0&&n.outTangents!==void 0}var ms=class{constructor(e,t,i,r){this.parameterPositions=e,this._cachedIndex=0,this.resultBuffer=r!==void 0?r:new t.constructor(i),this.sampleValues=t,this.valueSize=i,this.settings=null,this.DefaultSettings_={}}evaluate(e){let t=this.parameterPositions,i=this._cachedIndex,r=t[i],s=t[i-1];n:{e:{let o;t:{i:if(!(e<r)){for(let a=i+2;;){if(r===void 0){if(e<s)break i;return i=t.length,this._cachedIndex=i,this.copySampleValue_(i-1)}if(i===a)break;if(s=r,r=t[++i],e<r)break e}o=t.length;break t}if(!(e>=s)){let a=t[1];e<a&&(i=2,s=a);for(let l=i-2;;){if(s===void 0)return this._cachedIndex=0,this.copySampleValue_(0);if(i===l)break;if(r=s,s=t[--i-1],e>=s)break e}o=i,i=0;break t}break n}for(;i<o;){let a=i+o>>>1;e<t[a]?o=a:i=a+1}if(r=t[i],s=t[i-1],s===void 0)return this._cachedIndex=0,this.copySampleValue_(0);if(r===void 0)return i=t.length,this._cachedIndex=i,this.copySampleValue_(i-1)}this._cachedIndex=i,this.intervalChanged_(i,s,r)}return this.interpolate_(i,s,e,r)}getSettings_(){return this.settings||this.DefaultSettings_}copySampleValue_(e){let t=this.resultBuffer,i=this.sampleValues,r=this.valueSize,s=e*r;for(let o=0;o!==r;++o)t[o]=i[s+o];return t}interpolate_(){throw new Error("THREE.Interpolant: Call to abstract method.")}intervalChanged_(){}},oh=class extends ms{constructor(e,t,i,r){super(e,t,i,r),this._weightPrev=-0,this._offsetPrev=-0,this._weightNext=-0,this._offsetNext=-0,this.DefaultSettings_={endingStart:qp,endingEnd:qp}}intervalChanged_(e,t,i){let r=this.parameterPositions,s=e-2,o=e+1,a=r[s],l=r[o];if(a===void 0)switch(this.getSettings_().endingStart){case Jp:s=e,a=2*t-i;break;case jp:s=r.length-2,a=t+r[s]-r[s+1];break;default:s=e,a=i}if(l===void 0)switch(this.getSettings_().endingEnd){case Jp:o=e,l=2*i-t;break;case jp:o=1,l=i+r[1]-r[0];break;default:o=e-1,l=t}let c=(i-t)*.5,u=this.valueSize;this._weightPrev=c/(t-a),this._weightNext=c/(l-i),this._offsetPrev=s*u,this._offsetNext=o*u}interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=e*a,c=l-a,u=this._offsetPrev,h=this._offsetNext,f=this._weightPrev,d=this._weightNext,p=(i-t)/(r-t),x=p*p,m=x*p,g=-f*m+2*f*x-f*p,v=(1+f)*m+(-1.5-2*f)*x+(-.5+f)*p+1,T=(-1-d)*m+(1.5+d)*x+.5*p,M=d*m-d*x;for(let R=0;R!==a;++R)s[R]=g*o[u+R]+v*o[c+R]+T*o[l+R]+M*o[h+R];return s}},ah=class extends ms{constructor(e,t,i,r){super(e,t,i,r)}interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=e*a,c=l-a,u=(i-t)/(r-t),h=1-u;for(let f=0;f!==a;++f)s[f]=o[c+f]*h+o[l+f]*u;return s}},lh=class extends ms{constructor(e,t,i,r){super(e,t,i,r)}interpolate_(e){return this.copySampleValue_(e-1)}},ch=class extends ms{interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=e*a,c=l-a,u=this.inTangents,h=this.outTangents;if(!u||!h){let p=(i-t)/(r-t),x=1-p;for(let m=0;m!==a;++m)s[m]=o[c+m]*x+o[l+m]*p;return s}let f=a*2,d=e-1;for(let p=0;p!==a;++p){let x=o[c+p],m=o[l+p],g=d*f+p*2,v=h[g],T=h[g+1],M=e*f+p*2,R=u[M],w=u[M+1],y=uT(i,t,v,R,r);s[p]=bb(y,x,T,w,m)}return s}};function bb(n,e,t,i,r){let s=1-n;return s*s*s*e+3*s*s*n*t+3*s*n*n*i+n*n*n*r}function cT(n,e,t,i,r){let s=1-n;return 3*s*s*(t-e)+6*s*n*(i-t)+3*n*n*(r-i)}function uT(n,e,t,i,r){let s=(n-e)/(r-e);for(let o=0;o<8;o++){let a=bb(s,e,t,i,r)-n;if(Math.abs(a)<1e-10)break;let l=cT(s,e,t,i,r);if(Math.abs(l)<1e-10)break;s=Math.max(0,Math.min(1,s-a/l))}return s}var Ri=class{constructor(e,t,i,r){if(e===void 0)throw new Error("THREE.KeyframeTrack: track name is undefined");if(t===void 0||t.length===0)throw new Error("THREE.KeyframeTrack: no keyframes in track named "+e);this.name=e,this.times=Wo(t,this.TimeBufferType),this.values=Wo(i,this.ValueBufferType),this.setInterpolation(r||this.DefaultInterpolation)}static toJSON(e){let t=e.constructor,i;if(t.toJSON!==this.toJSON)i=t.toJSON(e);else{i={name:e.name,times:Wo(e.times,Array),values:Wo(e.values,Array)};let r=e.getInterpolation();r!==e.DefaultInterpolation&&(i.interpolation=r),Du(e.settings)&&(i.settings={inTangents:Wo(e.settings.inTangents,Array),outTangents:Wo(e.settings.outTangents,Array)})}return i.type=e.ValueTypeName,i}InterpolantFactoryMethodDiscrete(e){return new lh(this.times,this.values,this.getValueSize(),e)}InterpolantFactoryMethodLinear(e){return new ah(this.times,this.values,this.getValueSize(),e)}InterpolantFactoryMethodSmooth(e){return new oh(this.times,this.values,this.getValueSize(),e)}InterpolantFactoryMethodBezier(e){let t=new ch(this.times,this.values,this.getValueSize(),e);return this.settings&&(t.inTangents=this.settings.inTangents,t.outTangents=this.settings.outTangents),t}setInterpolation(e){let t;switch(e){case fl:t=this.InterpolantFactoryMethodDiscrete;break;case Ku:t=this.InterpolantFactoryMethodLinear;break;case Fu:t=this.InterpolantFactoryMethodSmooth;break;case $p:t=this.InterpolantFactoryMethodBezier;break}if(t===void 0){let i="unsupported interpolation for "+this.ValueTypeName+" keyframe track named "+this.name;if(this.createInterpolant===void 0)if(e!==this.DefaultInterpolation)this.setInterpolation(this.DefaultInterpolation);else throw new Error(i);return Ke("KeyframeTrack:",i),this}return this.createInterpolant=t,this}getInterpolation(){switch(this.createInterpolant){case this.InterpolantFactoryMethodDiscrete:return fl;case this.InterpolantFactoryMethodLinear:return Ku;case this.InterpolantFactoryMethodSmooth:return Fu;case this.InterpolantFactoryMethodBezier:return $p}}getValueSize(){return this.values.length/this.times.length}shift(e){if(e!==0){let t=this.times;for(let i=0,r=t.length;i!==r;++i)t[i]+=e;Du(this.settings)&&(Rv(this.settings.inTangents,e),Rv(this.settings.outTangents,e))}return this}scale(e){if(e!==1){let t=this.times;for(let i=0,r=t.length;i!==r;++i)t[i]*=e;Du(this.settings)&&(Iv(this.settings.inTangents,e),Iv(this.settings.outTangents,e))}return this}trim(e,t){let i=this.times,r=i.length,s=0,o=r-1;for(;s!==r&&i[s]<e;)++s;for(;o!==-1&&i[o]>t;)--o;if(++o,s!==0||o!==r){s>=o&&(o=Math.max(o,1),s=o-1);let a=this.getValueSize();this.times=i.slice(s,o),this.values=this.values.slice(s*a,o*a)}return this}validate(){let e=!0,t=this.getValueSize();t-Math.floor(t)!==0&&(nt("KeyframeTrack: Invalid value size in track.",this),e=!1);let i=this.times,r=this.values,s=i.length;s===0&&(nt("KeyframeTrack: Track is empty.",this),e=!1);let o=null;for(let a=0;a!==s;a++){let l=i[a];if(typeof l=="number"&&isNaN(l)){nt("KeyframeTrack: Time is not a valid number.",this,a,l),e=!1;break}if(o!==null&&o>l){nt("KeyframeTrack: Out of order keys.",this,a,l,o),e=!1;break}o=l}if(r!==void 0&&A1(r))for(let a=0,l=r.length;a!==l;++a){let c=r[a];if(isNaN(c)){nt("KeyframeTrack: Value is not a valid number.",this,a,c),e=!1;break}}return e}optimize(){let e=this.times.slice(),t=this.values.slice(),i=this.getValueSize(),r=this.getInterpolation()===Fu,s=e.length-1,o=1;for(let a=1;a<s;++a){let l=!1,c=e[a],u=e[a+1];if(c!==u&&(a!==1||c!==e[0]))if(r)l=!0;else{let h=a*i,f=h-i,d=h+i;for(let p=0;p!==i;++p){let x=t[h+p];if(x!==t[f+p]||x!==t[d+p]){l=!0;break}}}if(l){if(a!==o){e[o]=e[a];let h=a*i,f=o*i;for(let d=0;d!==i;++d)t[f+d]=t[h+d]}++o}}if(s>0){e[o]=e[s];for(let a=s*i,l=o*i,c=0;c!==i;++c)t[l+c]=t[a+c];++o}return o!==e.length?(this.times=e.slice(0,o),this.values=t.slice(0,o*i)):(this.times=e,this.values=t),this}clone(){let e=this.times.slice(),t=this.values.slice(),i=this.constructor,r=new i(this.name,e,t);return r.createInterpolant=this.createInterpolant,Du(this.settings)&&(r.settings={inTangents:this.settings.inTangents.slice(),outTangents:this.settings.outTangents.slice()}),r}};function Rv(n,e){for(let t=0,i=n.length;t!==i;t+=2)n[t]+=e}function Iv(n,e){for(let t=0,i=n.length;t!==i;t+=2)n[t]*=e}Ri.prototype.ValueTypeName="";Ri.prototype.TimeBufferType=Float32Array;Ri.prototype.ValueBufferType=Float32Array;Ri.prototype.DefaultInterpolation=Ku;var gs=class extends Ri{constructor(e,t,i){super(e,t,i)}};gs.prototype.ValueTypeName="bool";gs.prototype.ValueBufferType=Array;gs.prototype.DefaultInterpolation=fl;gs.prototype.InterpolantFactoryMethodLinear=void 0;gs.prototype.InterpolantFactoryMethodSmooth=void 0;var uh=class extends Ri{constructor(e,t,i,r){super(e,t,i,r)}};uh.prototype.ValueTypeName="color";var hh=class extends Ri{constructor(e,t,i,r){super(e,t,i,r)}};hh.prototype.ValueTypeName="number";var fh=class extends ms{constructor(e,t,i,r){super(e,t,i,r)}interpolate_(e,t,i,r){let s=this.resultBuffer,o=this.sampleValues,a=this.valueSize,l=(i-t)/(r-t),c=e*a;for(let u=c+a;c!==u;c+=4)Gn.slerpFlat(s,0,o,c-a,o,c,l);return s}},Rl=class extends Ri{constructor(e,t,i,r){super(e,t,i,r)}InterpolantFactoryMethodLinear(e){return new fh(this.times,this.values,this.getValueSize(),e)}};Rl.prototype.ValueTypeName="quaternion";Rl.prototype.InterpolantFactoryMethodSmooth=void 0;var ys=class extends Ri{constructor(e,t,i){super(e,t,i)}};ys.prototype.ValueTypeName="string";ys.prototype.ValueBufferType=Array;ys.prototype.DefaultInterpolation=fl;ys.prototype.InterpolantFactoryMethodLinear=void 0;ys.prototype.InterpolantFactoryMethodSmooth=void 0;var dh=class extends Ri{constructor(e,t,i,r){super(e,t,i,r)}};dh.prototype.ValueTypeName="vector";var ph=class{constructor(e,t,i){let r=this,s=!1,o=0,a=0,l,c=[];this.onStart=void 0,this.onLoad=e,this.onProgress=t,this.onError=i,this._abortController=null,this.itemStart=function(u){a++,s===!1&&r.onStart!==void 0&&r.onStart(u,o,a),s=!0},this.itemEnd=function(u){o++,r.onProgress!==void 0&&r.onProgress(u,o,a),o===a&&(s=!1,r.onLoad!==void 0&&r.onLoad())},this.itemError=function(u){r.onError!==void 0&&r.onError(u)},this.resolveURL=function(u){return u=u.normalize("NFC"),l?l(u):u},this.setURLModifier=function(u){return l=u,this},this.addHandler=function(u,h){return c.push(u,h),this},this.removeHandler=function(u){let h=c.indexOf(u);return h!==-1&&c.splice(h,2),this},this.getHandler=function(u){for(let h=0,f=c.length;h<f;h+=2){let d=c[h],p=c[h+1];if(d.global&&(d.lastIndex=0),d.test(u))return p}return null},this.abort=function(){return this.abortController.abort(),this._abortController=null,this}}get abortController(){return this._abortController||(this._abortController=new AbortController),this._abortController}},Sb=new ph,mh=class{constructor(e){this.manager=e!==void 0?e:Sb,this.crossOrigin="anonymous",this.withCredentials=!1,this.path="",this.resourcePath="",this.requestHeader={},this.priority="auto",this.cache="default",typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("observe",{detail:this}))}load(){}loadAsync(e,t){let i=this;return new Promise(function(r,s){i.load(e,r,t,s)})}parse(){}setCrossOrigin(e){return this.crossOrigin=e,this}setWithCredentials(e){return this.withCredentials=e,this}setPath(e){return this.path=e,this}setResourcePath(e){return this.resourcePath=e,this}setRequestHeader(e){return this.requestHeader=e,this}setPriority(e){return this.priority=e,this}setCache(e){return this.cache=e,this}abort(){return this}};mh.DEFAULT_MATERIAL_NAME="__DEFAULT";var Il=class extends zn{static registerNode(e){this.prototype._lightNode=e}constructor(e,t=1){super(),this.isLight=!0,this.type="Light",this.color=new ft(e),this.intensity=t}copy(e,t){return super.copy(e,t),this.color.copy(e.color),this.intensity=e.intensity,this}toJSON(e){let t=super.toJSON(e);return t.object.color=this.color.getHex(),t.object.intensity=this.intensity,t}};var Kp=new Ht,Cv=new Y,Nv=new Y,gh=class{constructor(e){this.camera=e,this.intensity=1,this.bias=0,this.biasNode=null,this.normalBias=0,this.radius=1,this.blurSamples=8,this.mapSize=new it(512,512),this.mapType=di,this.map=null,this.mapPass=null,this.matrix=new Ht,this.autoUpdate=!0,this.needsUpdate=!1,this._frustum=new ps,this._frameExtents=new it(1,1),this._viewportCount=1,this._viewports=[new jt(0,0,1,1)]}getViewportCount(){return this._viewportCount}getCamera(){return this.camera}getFrustum(){return this._frustum}updateMatrices(e){let t=this.camera;Cv.setFromMatrixPosition(e.matrixWorld),t.position.copy(Cv),Nv.setFromMatrixPosition(e.target.matrixWorld),t.lookAt(Nv),t.updateMatrixWorld(),this._updateMatrix(t,this.matrix,this._frustum)}_updateMatrix(e,t,i,r){Kp.multiplyMatrices(e.projectionMatrix,e.matrixWorldInverse),i.setFromProjectionMatrix(Kp,e.coordinateSystem,e.reversedDepth);let s=this._frameExtents,o=r?r.z/s.x:1,a=r?r.w/s.y:1,l=r?r.x/s.x:0,c=r?r.y/s.y:0;e.coordinateSystem===$o||e.reversedDepth?t.set(.5*o,0,0,.5*o+l,0,.5*a,0,.5*a+c,0,0,1,0,0,0,0,1):t.set(.5*o,0,0,.5*o+l,0,.5*a,0,.5*a+c,0,0,.5,.5,0,0,0,1),t.multiply(Kp)}getViewport(e){return this._viewports[e]}getFrameExtents(){return this._frameExtents}dispose(){this.map&&this.map.dispose(),this.mapPass&&this.mapPass.dispose()}copy(e){return this.camera=e.camera.clone(),this.intensity=e.intensity,this.bias=e.bias,this.radius=e.radius,this.autoUpdate=e.autoUpdate,this.needsUpdate=e.needsUpdate,this.normalBias=e.normalBias,this.blurSamples=e.blurSamples,this.mapSize.copy(e.mapSize),this.mapType=e.mapType,this.biasNode=e.biasNode,this}clone(){return new this.constructor().copy(this)}toJSON(){let e={};return e.intensity=this.intensity,e.bias=this.bias,e.normalBias=this.normalBias,e.radius=this.radius,e.blurSamples=this.blurSamples,e.mapSize=this.mapSize.toArray(),e.mapType=this.mapType,e.camera=this.camera.toJSON(!1).object,delete e.camera.matrix,e}},Uu=new Y,Ou=new Gn,gr=new Y,Cl=class extends zn{constructor(){super(),this.isCamera=!0,this.type="Camera",this.matrixWorldInverse=new Ht,this.projectionMatrix=new Ht,this.projectionMatrixInverse=new Ht,this.coordinateSystem=Oi,this._reversedDepth=!1}get reversedDepth(){return this._reversedDepth}copy(e,t){return super.copy(e,t),this.matrixWorldInverse.copy(e.matrixWorldInverse),this.projectionMatrix.copy(e.projectionMatrix),this.projectionMatrixInverse.copy(e.projectionMatrixInverse),this.coordinateSystem=e.coordinateSystem,this}getWorldDirection(e){return super.getWorldDirection(e).negate()}updateMatrixWorld(e){super.updateMatrixWorld(e),this.matrixWorld.decompose(Uu,Ou,gr),gr.x===1&&gr.y===1&&gr.z===1?this.matrixWorldInverse.copy(this.matrixWorld).invert():this.matrixWorldInverse.compose(Uu,Ou,gr.set(1,1,1)).invert()}updateWorldMatrix(e,t,i=!1){super.updateWorldMatrix(e,t,i),this.matrixWorld.decompose(Uu,Ou,gr),gr.x===1&&gr.y===1&&gr.z===1?this.matrixWorldInverse.copy(this.matrixWorld).invert():this.matrixWorldInverse.compose(Uu,Ou,gr.set(1,1,1)).invert()}clone(){return new this.constructor().copy(this)}},us=new Y,Pv=new it,Lv=new it,ai=class extends Cl{constructor(e=50,t=1,i=.1,r=2e3){super(),this.isPerspectiveCamera=!0,this.type="PerspectiveCamera",this.fov=e,this.zoom=1,this.near=i,this.far=r,this.focus=10,this.aspect=t,this.view=null,this.filmGauge=35,this.filmOffset=0,this.updateProjectionMatrix()}copy(e,t){return super.copy(e,t),this.fov=e.fov,this.zoom=e.zoom,this.near=e.near,this.far=e.far,this.focus=e.focus,this.aspect=e.aspect,this.view=e.view===null?null:Object.assign({},e.view),this.filmGauge=e.filmGauge,this.filmOffset=e.filmOffset,this}setFocalLength(e){let t=.5*this.getFilmHeight()/e;this.fov=Jo*2*Math.atan(t),this.updateProjectionMatrix()}getFocalLength(){let e=Math.tan(ul*.5*this.fov);return .5*this.getFilmHeight()/e}getEffectiveFOV(){return Jo*2*Math.atan(Math.tan(ul*.5*this.fov)/this.zoom)}getFilmWidth(){return this.filmGauge*Math.min(this.aspect,1)}getFilmHeight(){return this.filmGauge/Math.max(this.aspect,1)}getViewBounds(e,t,i){us.set(-1,-1,.5).applyMatrix4(this.projectionMatrixInverse),t.set(us.x,us.y).multiplyScalar(-e/us.z),us.set(1,1,.5).applyMatrix4(this.projectionMatrixInverse),i.set(us.x,us.y).multiplyScalar(-e/us.z)}getViewSize(e,t){return this.getViewBounds(e,Pv,Lv),t.subVectors(Lv,Pv)}setViewOffset(e,t,i,r,s,o){this.aspect=e/t,this.view===null&&(this.view={enabled:!0,fullWidth:1,fullHeight:1,offsetX:0,offsetY:0,width:1,height:1}),this.view.enabled=!0,this.view.fullWidth=e,this.view.fullHeight=t,this.view.offsetX=i,this.view.offsetY=r,this.view.width=s,this.view.height=o,this.updateProjectionMatrix()}clearViewOffset(){this.view!==null&&(this.view.enabled=!1),this.updateProjectionMatrix()}updateProjectionMatrix(){let e=this.near,t=e*Math.tan(ul*.5*this.fov)/this.zoom,i=2*t,r=this.aspect*i,s=-.5*r,o=this.view;if(this.view!==null&&this.view.enabled){let l=o.fullWidth,c=o.fullHeight;s+=o.offsetX*r/l,t-=o.offsetY*i/c,r*=o.width/l,i*=o.height/c}let a=this.filmOffset;a!==0&&(s+=e*a/this.getFilmWidth()),this.projectionMatrix.makePerspective(s,s+r,t,t-i,e,this.far,this.coordinateSystem,this.reversedDepth),this.projectionMatrixInverse.copy(this.projectionMatrix).invert()}toJSON(e){let t=super.toJSON(e);return t.object.fov=this.fov,t.object.zoom=this.zoom,t.object.near=this.near,t.object.far=this.far,t.object.focus=this.focus,t.object.aspect=this.aspect,this.view!==null&&(t.object.view=Object.assign({},this.view)),t.object.filmGauge=this.filmGauge,t.object.filmOffset=this.filmOffset,t}};var Nl=class extends Cl{constructor(e=-1,t=1,i=1,r=-1,s=.1,o=2e3){super(),this.isOrthographicCamera=!0,this.type="OrthographicCamera",this.zoom=1,this.view=null,this.left=e,this.right=t,this.top=i,this.bottom=r,this.near=s,this.far=o,this.updateProjectionMatrix()}copy(e,t){return super.copy(e,t),this.left=e.left,this.right=e.right,this.top=e.top,this.bottom=e.bottom,this.near=e.near,this.far=e.far,this.zoom=e.zoom,this.view=e.view===null?null:Object.assign({},e.view),this}setViewOffset(e,t,i,r,s,o){this.view===null&&(this.view={enabled:!0,fullWidth:1,fullHeight:1,offsetX:0,offsetY:0,width:1,height:1}),this.view.enabled=!0,this.view.fullWidth=e,this.view.fullHeight=t,this.view.offsetX=i,this.view.offsetY=r,this.view.width=s,this.view.height=o,this.updateProjectionMatrix()}clearViewOffset(){this.view!==null&&(this.view.enabled=!1),this.updateProjectionMatrix()}updateProjectionMatrix(){let e=(this.right-this.left)/(2*this.zoom),t=(this.top-this.bottom)/(2*this.zoom),i=(this.right+this.left)/2,r=(this.top+this.bottom)/2,s=i-e,o=i+e,a=r+t,l=r-t;if(this.view!==null&&this.view.enabled){let c=(this.right-this.left)/this.view.fullWidth/this.zoom,u=(this.top-this.bottom)/this.view.fullHeight/this.zoom;s+=c*this.view.offsetX,o=s+c*this.view.width,a-=u*this.view.offsetY,l=a-u*this.view.height}this.projectionMatrix.makeOrthographic(s,o,a,l,this.near,this.far,this.coordinateSystem,this.reversedDepth),this.projectionMatrixInverse.copy(this.projectionMatrix).invert()}toJSON(e){let t=super.toJSON(e);return t.object.zoom=this.zoom,t.object.left=this.left,t.object.right=this.right,t.object.top=this.top,t.object.bottom=this.bottom,t.object.near=this.near,t.object.far=this.far,this.view!==null&&(t.object.view=Object.assign({},this.view)),t}},em=class extends gh{constructor(){super(new Nl(-5,5,5,-5,.5,500)),this.isDirectionalLightShadow=!0}},ra=class extends Il{constructor(e,t){super(e,t),this.isDirectionalLight=!0,this.type="DirectionalLight",this.position.copy(zn.DEFAULT_UP),this.updateMatrix(),this.target=new zn,this.shadow=new em}dispose(){super.dispose(),this.shadow.dispose()}copy(e){return super.copy(e),this.target=e.target.clone(),this.shadow=e.shadow.clone(),this}toJSON(e){let t=super.toJSON(e);return t.object.shadow=this.shadow.toJSON(),t.object.target=this.target.uuid,t}},Pl=class extends Il{constructor(e,t){super(e,t),this.isAmbientLight=!0,this.type="AmbientLight"}};var Xo=-90,Yo=1,sa=class extends zn{constructor(e,t,i){super(),this.type="CubeCamera",this.renderTarget=i,this.coordinateSystem=null,this.activeMipmapLevel=0;let r=new ai(Xo,Yo,e,t);r.layers=this.layers,this.add(r);let s=new ai(Xo,Yo,e,t);s.layers=this.layers,this.add(s);let o=new ai(Xo,Yo,e,t);o.layers=this.layers,this.add(o);let a=new ai(Xo,Yo,e,t);a.layers=this.layers,this.add(a);let l=new ai(Xo,Yo,e,t);l.layers=this.layers,this.add(l);let c=new ai(Xo,Yo,e,t);c.layers=this.layers,this.add(c)}updateCoordinateSystem(){let e=this.coordinateSystem,t=this.children.concat(),[i,r,s,o,a,l]=t;for(let c of t)this.remove(c);if(e===Oi)i.up.set(0,1,0),i.lookAt(1,0,0),r.up.set(0,1,0),r.lookAt(-1,0,0),s.up.set(0,0,-1),s.lookAt(0,1,0),o.up.set(0,0,1),o.lookAt(0,-1,0),a.up.set(0,1,0),a.lookAt(0,0,1),l.up.set(0,1,0),l.lookAt(0,0,-1);else if(e===$o)i.up.set(0,-1,0),i.lookAt(-1,0,0),r.up.set(0,-1,0),r.lookAt(1,0,0),s.up.set(0,0,1),s.lookAt(0,1,0),o.up.set(0,0,-1),o.lookAt(0,-1,0),a.up.set(0,-1,0),a.lookAt(0,0,1),l.up.set(0,-1,0),l.lookAt(0,0,-1);else throw new Error("THREE.CubeCamera.updateCoordinateSystem(): Invalid coordinate system: "+e);for(let c of t)this.add(c),c.updateMatrixWorld()}update(e,t){this.parent===null&&this.updateMatrixWorld();let{renderTarget:i,activeMipmapLevel:r}=this;this.coordinateSystem!==e.coordinateSystem&&(this.coordinateSystem=e.coordinateSystem,this.updateCoordinateSystem());let[s,o,a,l,c,u]=this.children,h=e.getRenderTarget(),f=e.getActiveCubeFace(),d=e.getActiveMipmapLevel(),p=e.xr.enabled;e.xr.enabled=!1;let x=i.texture.mipmapsAutoUpdate;i.texture.mipmapsAutoUpdate=!1;let m=!1;e.isWebGLRenderer===!0?m=e.state.buffers.depth.getReversed():m=e.reversedDepthBuffer,e.setRenderTarget(i,0,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,s),e.setRenderTarget(i,1,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,o),e.setRenderTarget(i,2,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,a),e.setRenderTarget(i,3,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,l),e.setRenderTarget(i,4,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,c),i.texture.mipmapsAutoUpdate=x,e.setRenderTarget(i,5,r),m&&e.autoClear===!1&&e.clearDepth(),e.render(t,u),e.setRenderTarget(h,f,d),e.xr.enabled=p,i.texture.needsPMREMUpdate=!0}},yh=class extends ai{constructor(e=[]){super(),this.isArrayCamera=!0,this.isMultiViewCamera=!1,this.cameras=e,this.perCameraFrustumCulled=!1}};var Dm="\\[\\]\\.:\\/",hT=new RegExp("["+Dm+"]","g"),Um="[^"+Dm+"]",fT="[^"+Dm.replace("\\.","")+"]",dT=/((?:WC+[\/:])*)/.source.replace("WC",Um),pT=/(WCOD+)?/.source.replace("WCOD",fT),mT=/(?:\.(WC+)(?:\[(.+)\])?)?/.source.replace("WC",Um),gT=/\.(WC+)(?:\[(.+)\])?/.source.replace("WC",Um),yT=new RegExp("^"+dT+pT+mT+gT+"$"),_T=["material","materials","bones","map"],tm=class{constructor(e,t,i){let r=i||$t.parseTrackName(t);this._targetGroup=e,this._bindings=e.subscribe_(t,r)}getValue(e,t){this.bind();let i=this._targetGroup.nCachedObjects_,r=this._bindings[i];r!==void 0&&r.getValue(e,t)}setValue(e,t){let i=this._bindings;for(let r=this._targetGroup.nCachedObjects_,s=i.length;r!==s;++r)i[r].setValue(e,t)}bind(){let e=this._bindings;for(let t=this._targetGroup.nCachedObjects_,i=e.length;t!==i;++t)e[t].bind()}unbind(){let e=this._bindings;for(let t=this._targetGroup.nCachedObjects_,i=e.length;t!==i;++t)e[t].unbind()}},$t=class n{constructor(e,t,i){this.path=t,this.parsedPath=i||n.parseTrackName(t),this.node=n.findNode(e,this.parsedPath.nodeName),this.rootNode=e,this.getValue=this._getValue_unbound,this.setValue=this._setValue_unbound}static create(e,t,i){return e&&e.isAnimationObjectGroup?new n.Composite(e,t,i):new n(e,t,i)}static sanitizeNodeName(e){return e.replace(/\s/g,"_").replace(hT,"")}static parseTrackName(e){let t=yT.exec(e);if(t===null)throw new Error("THREE.PropertyBinding: Cannot parse trackName: "+e);let i={nodeName:t[2],objectName:t[3],objectIndex:t[4],propertyName:t[5],propertyIndex:t[6]},r=i.nodeName&&i.nodeName.lastIndexOf(".");if(r!==void 0&&r!==-1){let s=i.nodeName.substring(r+1);_T.indexOf(s)!==-1&&(i.nodeName=i.nodeName.substring(0,r),i.objectName=s)}if(i.propertyName===null||i.propertyName.length===0)throw new Error("THREE.PropertyBinding: can not parse propertyName from trackName: "+e);return i}static findNode(e,t){if(t===void 0||t===""||t==="."||t===-1||t===e.name||t===e.uuid)return e;if(e.skeleton){let i=e.skeleton.getBoneByName(t);if(i!==void 0)return i}if(e.children){let i=function(s){for(let o=0;o<s.length;o++){let a=s[o];if(a.name===t||a.uuid===t)return a;let l=i(a.children);if(l)return l}return null},r=i(e.children);if(r)return r}return null}_getValue_unavailable(){}_setValue_unavailable(){}_getValue_direct(e,t){e[t]=this.targetObject[this.propertyName]}_getValue_array(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)e[t++]=i[r]}_getValue_arrayElement(e,t){e[t]=this.resolvedProperty[this.propertyIndex]}_getValue_toArray(e,t){this.resolvedProperty.toArray(e,t)}_setValue_direct(e,t){this.targetObject[this.propertyName]=e[t]}_setValue_direct_setNeedsUpdate(e,t){this.targetObject[this.propertyName]=e[t],this.targetObject.needsUpdate=!0}_setValue_direct_setMatrixWorldNeedsUpdate(e,t){this.targetObject[this.propertyName]=e[t],this.targetObject.matrixWorldNeedsUpdate=!0}_setValue_array(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)i[r]=e[t++]}_setValue_array_setNeedsUpdate(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)i[r]=e[t++];this.targetObject.needsUpdate=!0}_setValue_array_setMatrixWorldNeedsUpdate(e,t){let i=this.resolvedProperty;for(let r=0,s=i.length;r!==s;++r)i[r]=e[t++];this.targetObject.matrixWorldNeedsUpdate=!0}_setValue_arrayElement(e,t){this.resolvedProperty[this.propertyIndex]=e[t]}_setValue_arrayElement_setNeedsUpdate(e,t){this.resolvedProperty[this.propertyIndex]=e[t],this.targetObject.needsUpdate=!0}_setValue_arrayElement_setMatrixWorldNeedsUpdate(e,t){this.resolvedProperty[this.propertyIndex]=e[t],this.targetObject.matrixWorldNeedsUpdate=!0}_setValue_fromArray(e,t){this.resolvedProperty.fromArray(e,t)}_setValue_fromArray_setNeedsUpdate(e,t){this.resolvedProperty.fromArray(e,t),this.targetObject.needsUpdate=!0}_setValue_fromArray_setMatrixWorldNeedsUpdate(e,t){this.resolvedProperty.fromArray(e,t),this.targetObject.matrixWorldNeedsUpdate=!0}_getValue_unbound(e,t){this.bind(),this.getValue(e,t)}_setValue_unbound(e,t){this.bind(),this.setValue(e,t)}bind(){let e=this.node,t=this.parsedPath,i=t.objectName,r=t.propertyName,s=t.propertyIndex;if(e||(e=n.findNode(this.rootNode,t.nodeName),this.node=e),this.getValue=this._getValue_unavailable,this.setValue=this._setValue_unavailable,!e){Ke("PropertyBinding: No target node found for track: "+this.path+".");return}if(i){let c=t.objectIndex;switch(i){case"materials":if(!e.material){nt("PropertyBinding: Can not bind to material as node does not have a material.",this);return}if(!e.material.materials){nt("PropertyBinding: Can not bind to material.materials as node.material does not have a materials array.",this);return}e=e.material.materials;break;case"bones":if(!e.skeleton){nt("PropertyBinding: Can not bind to bones as node does not have a skeleton.",this);return}e=e.skeleton.bones;for(let u=0;u<e.length;u++)if(e[u].name===c){c=u;break}break;case"map":if("map"in e){e=e.map;break}if(!e.material){nt("PropertyBinding: Can not bind to material as node does not have a material.",this);return}if(!e.material.map){nt("PropertyBinding: Can not bind to material.map as node.material does not have a map.",this);return}e=e.material.map;break;default:if(e[i]===void 0){nt("PropertyBinding: Can not bind to objectName of node undefined.",this);return}e=e[i]}if(c!==void 0){if(e[c]===void 0){nt("PropertyBinding: Trying to bind to objectIndex of objectName, but is undefined.",this,e);return}e=e[c]}}let o=e[r];if(o===void 0){let c=t.nodeName;nt("PropertyBinding: Trying to update property for track: "+c+"."+r+" but it wasn't found.",e);return}let a=this.Versioning.None;this.targetObject=e,e.isMaterial===!0?a=this.Versioning.NeedsUpdate:e.isObject3D===!0&&(a=this.Versioning.MatrixWorldNeedsUpdate);let l=this.BindingType.Direct;if(s!==void 0){if(r==="morphTargetInfluences"){if(!e.geometry){nt("PropertyBinding: Can not bind to morphTargetInfluences because node does not have a geometry.",this);return}if(!e.geometry.morphAttributes){nt("PropertyBinding: Can not bind to morphTargetInfluences because node does not have a geometry.morphAttributes.",this);return}e.morphTargetDictionary[s]!==void 0&&(s=e.morphTargetDictionary[s])}l=this.BindingType.ArrayElement,this.resolvedProperty=o,this.propertyIndex=s}else o.fromArray!==void 0&&o.toArray!==void 0?(l=this.BindingType.HasFromToArray,this.resolvedProperty=o):Array.isArray(o)?(l=this.BindingType.EntireArray,this.resolvedProperty=o):this.propertyName=r;this.getValue=this.GetterByBindingType[l],this.setValue=this.SetterByBindingTypeAndVersioning[l][a]}unbind(){this.node=null,this.getValue=this._getValue_unbound,this.setValue=this._setValue_unbound}};$t.Composite=tm;$t.prototype.BindingType={Direct:0,EntireArray:1,ArrayElement:2,HasFromToArray:3};$t.prototype.Versioning={None:0,NeedsUpdate:1,MatrixWorldNeedsUpdate:2};$t.prototype.GetterByBindingType=[$t.prototype._getValue_direct,$t.prototype._getValue_array,$t.prototype._getValue_arrayElement,$t.prototype._getValue_toArray];$t.prototype.SetterByBindingTypeAndVersioning=[[$t.prototype._setValue_direct,$t.prototype._setValue_direct_setNeedsUpdate,$t.prototype._setValue_direct_setMatrixWorldNeedsUpdate],[$t.prototype._setValue_array,$t.prototype._setValue_array_setNeedsUpdate,$t.prototype._setValue_array_setMatrixWorldNeedsUpdate],[$t.prototype._setValue_arrayElement,$t.prototype._setValue_arrayElement_setNeedsUpdate,$t.prototype._setValue_arrayElement_setMatrixWorldNeedsUpdate],[$t.prototype._setValue_fromArray,$t.prototype._setValue_fromArray_setNeedsUpdate,$t.prototype._setValue_fromArray_setMatrixWorldNeedsUpdate]];var kF=new Float32Array(1);var oa=class{constructor(e=1,t=0,i=0){this.radius=e,this.phi=t,this.theta=i}set(e,t,i){return this.radius=e,this.phi=t,this.theta=i,this}copy(e){return this.radius=e.radius,this.phi=e.phi,this.theta=e.theta,this}makeSafe(){return this.phi=gt(this.phi,1e-6,Math.PI-1e-6),this}setFromVector3(e){return this.setFromCartesianCoords(e.x,e.y,e.z)}setFromCartesianCoords(e,t,i){return this.radius=Math.sqrt(e*e+t*t+i*i),this.radius===0?(this.theta=0,this.phi=0):(this.theta=Math.atan2(e,i),this.phi=Math.acos(gt(t/this.radius,-1,1))),this}clone(){return new this.constructor().copy(this)}};var nm=class{static{this.prototype.isMatrix2=!0}constructor(e,t,i,r){this.elements=[1,0,0,1],e!==void 0&&this.set(e,t,i,r)}identity(){return this.set(1,0,0,1),this}fromArray(e,t=0){for(let i=0;i<4;i++)this.elements[i]=e[i+t];return this}set(e,t,i,r){let s=this.elements;return s[0]=e,s[2]=t,s[1]=i,s[3]=r,this}};var Ll=class extends ji{constructor(e,t=null){super(),this.object=e,this.domElement=t,this.enabled=!0,this.state=-1,this.keys={},this.mouseButtons={LEFT:null,MIDDLE:null,RIGHT:null},this.touches={ONE:null,TWO:null}}connect(e){this.domElement!==null&&this.disconnect(),this.domElement=e}disconnect(){}dispose(){}update(){}};function Om(n,e,t,i){let r=xT(i);switch(t){case bm:return n*e;case Mm:return n*e/r.components*r.byteLength;case wh:return n*e/r.components*r.byteLength;case bs:return n*e*2/r.components*r.byteLength;case Ah:return n*e*2/r.components*r.byteLength;case Sm:return n*e*3/r.components*r.byteLength;case nr:return n*e*4/r.components*r.byteLength;case Th:return n*e*4/r.components*r.byteLength;case Ol:case Fl:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*8;case Bl:case kl:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*16;case Ih:case Nh:return Math.max(n,16)*Math.max(e,8)/4;case Rh:case Ch:return Math.max(n,8)*Math.max(e,8)/2;case Ph:case Lh:case Uh:case Oh:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*8;case Dh:case Vl:case Fh:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*16;case Bh:return Math.floor((n+3)/4)*Math.floor((e+3)/4)*16;case kh:return Math.floor((n+4)/5)*Math.floor((e+3)/4)*16;case Vh:return Math.floor((n+4)/5)*Math.floor((e+4)/5)*16;case Gh:return Math.floor((n+5)/6)*Math.floor((e+4)/5)*16;case zh:return Math.floor((n+5)/6)*Math.floor((e+5)/6)*16;case Hh:return Math.floor((n+7)/8)*Math.floor((e+4)/5)*16;case Wh:return Math.floor((n+7)/8)*Math.floor((e+5)/6)*16;case Xh:return Math.floor((n+7)/8)*Math.floor((e+7)/8)*16;case Yh:return Math.floor((n+9)/10)*Math.floor((e+4)/5)*16;case Zh:return Math.floor((n+9)/10)*Math.floor((e+5)/6)*16;case Kh:return Math.floor((n+9)/10)*Math.floor((e+7)/8)*16;case $h:return Math.floor((n+9)/10)*Math.floor((e+9)/10)*16;case qh:return Math.floor((n+11)/12)*Math.floor((e+9)/10)*16;case Jh:return Math.floor((n+11)/12)*Math.floor((e+11)/12)*16;case jh:case Qh:case ef:return Math.ceil(n/4)*Math.ceil(e/4)*16;case tf:case nf:return Math.ceil(n/4)*Math.ceil(e/4)*8;case Gl:case rf:return Math.ceil(n/4)*Math.ceil(e/4)*16}throw new Error(`Unable to determine texture byte length for ${t} format.`)}function xT(n){switch(n){case di:case ym:return{byteLength:1,components:1};case ua:case _m:case tr:return{byteLength:2,components:1};case Mh:case Eh:return{byteLength:2,components:4};case Qi:case Sh:case er:return{byteLength:4,components:1};case xm:case vm:return{byteLength:4,components:3}}throw new Error(`THREE.TextureUtils: Unknown texture type ${n}.`)}typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("register",{detail:{revision:"187"}}));typeof window<"u"&&(window.__THREE__?Ke("WARNING: Multiple instances of Three.js being imported."):window.__THREE__="187");function Wb(){let n=null,e=!1,t=null,i=null;function r(s,o){i=n.requestAnimationFrame(r),t(s,o)}return{start:function(){e!==!0&&t!==null&&n!==null&&(i=n.requestAnimationFrame(r),e=!0)},stop:function(){n!==null&&n.cancelAnimationFrame(i),e=!1},setAnimationLoop:function(s){t=s},setContext:function(s){n=s}}}function bT(n){let e=new WeakMap;function t(a,l){let c=a.array,u=a.usage,h=c.byteLength,f=n.createBuffer();n.bindBuffer(l,f),n.bufferData(l,c,u),a.onUploadCallback();let d;if(c instanceof Float32Array)d=n.FLOAT;else if(typeof Float16Array<"u"&&c instanceof Float16Array)d=n.HALF_FLOAT;else if(c instanceof Uint16Array)a.isFloat16BufferAttribute?d=n.HALF_FLOAT:d=n.UNSIGNED_SHORT;else if(c instanceof Int16Array)d=n.SHORT;else if(c instanceof Uint32Array)d=n.UNSIGNED_INT;else if(c instanceof Int32Array)d=n.INT;else if(c instanceof Int8Array)d=n.BYTE;else if(c instanceof Uint8Array)d=n.UNSIGNED_BYTE;else if(c instanceof Uint8ClampedArray)d=n.UNSIGNED_BYTE;else throw new Error("THREE.WebGLAttributes: Unsupported buffer data format: "+c);return{buffer:f,type:d,bytesPerElement:c.BYTES_PER_ELEMENT,version:a.version,size:h}}function i(a,l,c){let u=l.array,h=l.updateRanges;if(n.bindBuffer(c,a),h.length===0)n.bufferSubData(c,0,u);else{h.sort((d,p)=>d.start-p.start);let f=0;for(let d=1;d<h.length;d++){let p=h[f],x=h[d];x.start<=p.start+p.count+1?p.count=Math.max(p.count,x.start+x.count-p.start):(++f,h[f]=x)}h.length=f+1;for(let d=0,p=h.length;d<p;d++){let x=h[d];n.bufferSubData(c,x.start*u.BYTES_PER_ELEMENT,u,x.start,x.count)}l.clearUpdateRanges()}l.onUploadCallback()}function r(a){return a.isInterleavedBufferAttribute&&(a=a.data),e.get(a)}function s(a){a.isInterleavedBufferAttribute&&(a=a.data);let l=e.get(a);l&&(n.deleteBuffer(l.buffer),e.delete(a))}function o(a,l){if(a.isInterleavedBufferAttribute&&(a=a.data),a.isGLBufferAttribute){let u=e.get(a);(!u||u.version<a.version)&&e.set(a,{buffer:a.buffer,type:a.type,bytesPerElement:a.elementSize,version:a.version});return}let c=e.get(a);if(c===void 0)e.set(a,t(a,l));else if(c.version<a.version){if(c.size!==a.array.byteLength)throw new Error("THREE.WebGLAttributes: The size of the buffer attribute's array buffer does not match the original size. Resizing buffer attributes is not supported.");i(c.buffer,a,l),c.version=a.version}}return{get:r,remove:s,update:o}}var ST=`#ifdef USE_ALPHAHASH
	if ( diffuseColor.a < getAlphaHashThreshold( vPosition ) ) discard;
#endif`,MT=`#ifdef USE_ALPHAHASH
	const float ALPHA_HASH_SCALE = 0.05;
	float hash2D( vec2 value ) {
		return fract( 1.0e4 * sin( 17.0 * value.x + 0.1 * value.y ) * ( 0.1 + abs( sin( 13.0 * value.y + value.x ) ) ) );
	}
	float hash3D( vec3 value ) {
		return hash2D( vec2( hash2D( value.xy ), value.z ) );
	}
	float getAlphaHashThreshold( vec3 position ) {
		float maxDeriv = max(
			length( dFdx( position.xyz ) ),
			length( dFdy( position.xyz ) )
		);
		float pixScale = 1.0 / ( ALPHA_HASH_SCALE * maxDeriv );
		vec2 pixScales = vec2(
			exp2( floor( log2( pixScale ) ) ),
			exp2( ceil( log2( pixScale ) ) )
		);
		vec2 alpha = vec2(
			hash3D( floor( pixScales.x * position.xyz ) ),
			hash3D( floor( pixScales.y * position.xyz ) )
		);
		float lerpFactor = fract( log2( pixScale ) );
		float x = ( 1.0 - lerpFactor ) * alpha.x + lerpFactor * alpha.y;
		float a = min( lerpFactor, 1.0 - lerpFactor );
		vec3 cases = vec3(
			x * x / ( 2.0 * a * ( 1.0 - a ) ),
			( x - 0.5 * a ) / ( 1.0 - a ),
			1.0 - ( ( 1.0 - x ) * ( 1.0 - x ) / ( 2.0 * a * ( 1.0 - a ) ) )
		);
		float threshold = ( x < ( 1.0 - a ) )
			? ( ( x < a ) ? cases.x : cases.y )
			: cases.z;
		return clamp( threshold , 1.0e-6, 1.0 );
	}
#endif`,ET=`#ifdef USE_ALPHAMAP
	diffuseColor.a *= texture2D( alphaMap, vAlphaMapUv ).g;
#endif`,wT=`#ifdef USE_ALPHAMAP
	uniform sampler2D alphaMap;
#endif`,AT=`#ifdef USE_ALPHATEST
	#ifdef ALPHA_TO_COVERAGE
	diffuseColor.a = smoothstep( alphaTest, alphaTest + fwidth( diffuseColor.a ), diffuseColor.a );
	if ( diffuseColor.a == 0.0 ) discard;
	#else
	if ( diffuseColor.a < alphaTest ) discard;
	#endif
#endif`,TT=`#ifdef USE_ALPHATEST
	uniform float alphaTest;
#endif`,RT=`#ifdef USE_AOMAP
	float ambientOcclusion = ( texture2D( aoMap, vAoMapUv ).r - 1.0 ) * aoMapIntensity + 1.0;
	reflectedLight.indirectDiffuse *= ambientOcclusion;
	#if defined( USE_CLEARCOAT ) 
		clearcoatSpecularIndirect *= ambientOcclusion;
	#endif
	#if defined( USE_SHEEN ) 
		sheenSpecularIndirect *= ambientOcclusion;
	#endif
	#if defined( USE_ENVMAP ) && defined( STANDARD )
		float dotNV = saturate( dot( geometryNormal, geometryViewDir ) );
		reflectedLight.indirectSpecular *= computeSpecularOcclusion( dotNV, ambientOcclusion, material.roughness );
	#endif
#endif`,IT=`#ifdef USE_AOMAP
	uniform sampler2D aoMap;
	uniform float aoMapIntensity;
#endif`,CT=`#ifdef USE_BATCHING
	#if ! defined( GL_ANGLE_multi_draw )
	#define gl_DrawID _gl_DrawID
	uniform int _gl_DrawID;
	#endif
	uniform highp sampler2D batchingTexture;
	uniform highp usampler2D batchingIdTexture;
	mat4 getBatchingMatrix( const in float i ) {
		int size = textureSize( batchingTexture, 0 ).x;
		int j = int( i ) * 4;
		int x = j % size;
		int y = j / size;
		vec4 v1 = texelFetch( batchingTexture, ivec2( x, y ), 0 );
		vec4 v2 = texelFetch( batchingTexture, ivec2( x + 1, y ), 0 );
		vec4 v3 = texelFetch( batchingTexture, ivec2( x + 2, y ), 0 );
		vec4 v4 = texelFetch( batchingTexture, ivec2( x + 3, y ), 0 );
		return mat4( v1, v2, v3, v4 );
	}
	float getIndirectIndex( const in int i ) {
		int size = textureSize( batchingIdTexture, 0 ).x;
		int x = i % size;
		int y = i / size;
		return float( texelFetch( batchingIdTexture, ivec2( x, y ), 0 ).r );
	}
#endif
#ifdef USE_BATCHING_COLOR
	uniform sampler2D batchingColorTexture;
	vec4 getBatchingColor( const in float i ) {
		int size = textureSize( batchingColorTexture, 0 ).x;
		int j = int( i );
		int x = j % size;
		int y = j / size;
		return texelFetch( batchingColorTexture, ivec2( x, y ), 0 );
	}
#endif`,NT=`#ifdef USE_BATCHING
	mat4 batchingMatrix = getBatchingMatrix( getIndirectIndex( gl_DrawID ) );
#endif`,PT=`vec3 transformed = vec3( position );
#ifdef USE_ALPHAHASH
	vPosition = vec3( position );
#endif`,LT=`vec3 objectNormal = vec3( normal );
#ifdef USE_TANGENT
	vec3 objectTangent = vec3( tangent.xyz );
#endif`,DT=`float G_BlinnPhong_Implicit( ) {
	return 0.25;
}
float D_BlinnPhong( const in float shininess, const in float dotNH ) {
	return RECIPROCAL_PI * ( shininess * 0.5 + 1.0 ) * pow( dotNH, shininess );
}
vec3 BRDF_BlinnPhong( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in vec3 specularColor, const in float shininess ) {
	vec3 halfDir = normalize( lightDir + viewDir );
	float dotNH = saturate( dot( normal, halfDir ) );
	float dotVH = saturate( dot( viewDir, halfDir ) );
	vec3 F = F_Schlick( specularColor, 1.0, dotVH );
	float G = G_BlinnPhong_Implicit( );
	float D = D_BlinnPhong( shininess, dotNH );
	return F * ( G * D );
} // validated`,UT=`#ifdef USE_IRIDESCENCE
	const mat3 XYZ_TO_REC709 = mat3(
		 3.2404542, -0.9692660,  0.0556434,
		-1.5371385,  1.8760108, -0.2040259,
		-0.4985314,  0.0415560,  1.0572252
	);
	vec3 Fresnel0ToIor( vec3 fresnel0 ) {
		vec3 sqrtF0 = sqrt( fresnel0 );
		return ( vec3( 1.0 ) + sqrtF0 ) / ( vec3( 1.0 ) - sqrtF0 );
	}
	vec3 IorToFresnel0( vec3 transmittedIor, float incidentIor ) {
		return pow2( ( transmittedIor - vec3( incidentIor ) ) / ( transmittedIor + vec3( incidentIor ) ) );
	}
	float IorToFresnel0( float transmittedIor, float incidentIor ) {
		return pow2( ( transmittedIor - incidentIor ) / ( transmittedIor + incidentIor ));
	}
	vec3 evalSensitivity( float OPD, vec3 shift ) {
		float phase = 2.0 * PI * OPD * 1.0e-9;
		vec3 val = vec3( 5.4856e-13, 4.4201e-13, 5.2481e-13 );
		vec3 pos = vec3( 1.6810e+06, 1.7953e+06, 2.2084e+06 );
		vec3 var = vec3( 4.3278e+09, 9.3046e+09, 6.6121e+09 );
		vec3 xyz = val * sqrt( 2.0 * PI * var ) * cos( pos * phase + shift ) * exp( - pow2( phase ) * var );
		xyz.x += 9.7470e-14 * sqrt( 2.0 * PI * 4.5282e+09 ) * cos( 2.2399e+06 * phase + shift[ 0 ] ) * exp( - 4.5282e+09 * pow2( phase ) );
		xyz /= 1.0685e-7;
		vec3 rgb = XYZ_TO_REC709 * xyz;
		return rgb;
	}
	vec3 evalIridescence( float outsideIOR, float eta2, float cosTheta1, float thinFilmThickness, vec3 baseF0 ) {
		vec3 I;
		float iridescenceIOR = mix( outsideIOR, eta2, smoothstep( 0.0, 0.03, thinFilmThickness ) );
		float sinTheta2Sq = pow2( outsideIOR / iridescenceIOR ) * ( 1.0 - pow2( cosTheta1 ) );
		float cosTheta2Sq = 1.0 - sinTheta2Sq;
		if ( cosTheta2Sq < 0.0 ) {
			return vec3( 1.0 );
		}
		float cosTheta2 = sqrt( cosTheta2Sq );
		float R0 = IorToFresnel0( iridescenceIOR, outsideIOR );
		float R12 = F_Schlick( R0, 1.0, cosTheta1 );
		float T121 = 1.0 - R12;
		float phi12 = 0.0;
		if ( iridescenceIOR < outsideIOR ) phi12 = PI;
		float phi21 = PI - phi12;
		vec3 baseIOR = Fresnel0ToIor( clamp( baseF0, 0.0, 0.9999 ) );		vec3 R1 = IorToFresnel0( baseIOR, iridescenceIOR );
		vec3 R23 = F_Schlick( R1, 1.0, cosTheta2 );
		vec3 phi23 = vec3( 0.0 );
		if ( baseIOR[ 0 ] < iridescenceIOR ) phi23[ 0 ] = PI;
		if ( baseIOR[ 1 ] < iridescenceIOR ) phi23[ 1 ] = PI;
		if ( baseIOR[ 2 ] < iridescenceIOR ) phi23[ 2 ] = PI;
		float OPD = 2.0 * iridescenceIOR * thinFilmThickness * cosTheta2;
		vec3 phi = vec3( phi21 ) + phi23;
		vec3 R123 = clamp( R12 * R23, 1e-5, 0.9999 );
		vec3 r123 = sqrt( R123 );
		vec3 Rs = pow2( T121 ) * R23 / ( vec3( 1.0 ) - R123 );
		vec3 C0 = R12 + Rs;
		I = C0;
		vec3 Cm = Rs - T121;
		for ( int m = 1; m <= 2; ++ m ) {
			Cm *= r123;
			vec3 Sm = 2.0 * evalSensitivity( float( m ) * OPD, float( m ) * phi );
			I += Cm * Sm;
		}
		return max( I, vec3( 0.0 ) );
	}
#endif`,OT=`#ifdef USE_BUMPMAP
	uniform sampler2D bumpMap;
	uniform float bumpScale;
	vec2 dHdxy_fwd() {
		vec2 dSTdx = dFdx( vBumpMapUv );
		vec2 dSTdy = dFdy( vBumpMapUv );
		float Hll = bumpScale * texture2D( bumpMap, vBumpMapUv ).x;
		float dBx = bumpScale * texture2D( bumpMap, vBumpMapUv + dSTdx ).x - Hll;
		float dBy = bumpScale * texture2D( bumpMap, vBumpMapUv + dSTdy ).x - Hll;
		return vec2( dBx, dBy );
	}
	vec3 perturbNormalArb( vec3 surf_pos, vec3 surf_norm, vec2 dHdxy, float faceDirection ) {
		vec3 vSigmaX = normalize( dFdx( surf_pos.xyz ) );
		vec3 vSigmaY = normalize( dFdy( surf_pos.xyz ) );
		vec3 vN = surf_norm;
		vec3 R1 = cross( vSigmaY, vN );
		vec3 R2 = cross( vN, vSigmaX );
		float fDet = dot( vSigmaX, R1 ) * faceDirection;
		vec3 vGrad = sign( fDet ) * ( dHdxy.x * R1 + dHdxy.y * R2 );
		return normalize( abs( fDet ) * surf_norm - vGrad );
	}
#endif`,FT=`#if NUM_CLIPPING_PLANES > 0
	vec4 plane;
	#ifdef ALPHA_TO_COVERAGE
		float distanceToPlane, distanceGradient;
		float clipOpacity = 1.0;
		#pragma unroll_loop_start
		for ( int i = 0; i < UNION_CLIPPING_PLANES; i ++ ) {
			plane = clippingPlanes[ i ];
			distanceToPlane = - dot( vClipPosition, plane.xyz ) + plane.w;
			distanceGradient = fwidth( distanceToPlane ) / 2.0;
			clipOpacity *= smoothstep( - distanceGradient, distanceGradient, distanceToPlane );
			if ( clipOpacity == 0.0 ) discard;
		}
		#pragma unroll_loop_end
		#if UNION_CLIPPING_PLANES < NUM_CLIPPING_PLANES
			float unionClipOpacity = 1.0;
			#pragma unroll_loop_start
			for ( int i = UNION_CLIPPING_PLANES; i < NUM_CLIPPING_PLANES; i ++ ) {
				plane = clippingPlanes[ i ];
				distanceToPlane = - dot( vClipPosition, plane.xyz ) + plane.w;
				distanceGradient = fwidth( distanceToPlane ) / 2.0;
				unionClipOpacity *= 1.0 - smoothstep( - distanceGradient, distanceGradient, distanceToPlane );
			}
			#pragma unroll_loop_end
			clipOpacity *= 1.0 - unionClipOpacity;
		#endif
		diffuseColor.a *= clipOpacity;
		if ( diffuseColor.a == 0.0 ) discard;
	#else
		#pragma unroll_loop_start
		for ( int i = 0; i < UNION_CLIPPING_PLANES; i ++ ) {
			plane = clippingPlanes[ i ];
			if ( dot( vClipPosition, plane.xyz ) > plane.w ) discard;
		}
		#pragma unroll_loop_end
		#if UNION_CLIPPING_PLANES < NUM_CLIPPING_PLANES
			bool clipped = true;
			#pragma unroll_loop_start
			for ( int i = UNION_CLIPPING_PLANES; i < NUM_CLIPPING_PLANES; i ++ ) {
				plane = clippingPlanes[ i ];
				clipped = ( dot( vClipPosition, plane.xyz ) > plane.w ) && clipped;
			}
			#pragma unroll_loop_end
			if ( clipped ) discard;
		#endif
	#endif
#endif`,BT=`#if NUM_CLIPPING_PLANES > 0
	varying vec3 vClipPosition;
	uniform vec4 clippingPlanes[ NUM_CLIPPING_PLANES ];
#endif`,kT=`#if NUM_CLIPPING_PLANES > 0
	varying vec3 vClipPosition;
#endif`,VT=`#if NUM_CLIPPING_PLANES > 0
	vClipPosition = - mvPosition.xyz;
#endif`,GT=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA )
	diffuseColor *= vColor;
#endif`,zT=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA )
	varying vec4 vColor;
#endif`,HT=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA ) || defined( USE_INSTANCING_COLOR ) || defined( USE_BATCHING_COLOR )
	varying vec4 vColor;
#endif`,WT=`#if defined( USE_COLOR ) || defined( USE_COLOR_ALPHA ) || defined( USE_INSTANCING_COLOR ) || defined( USE_BATCHING_COLOR )
	vColor = vec4( 1.0 );
#endif
#ifdef USE_COLOR_ALPHA
	vColor *= color;
#elif defined( USE_COLOR )
	vColor.rgb *= color;
#endif
#ifdef USE_INSTANCING_COLOR
	vColor.rgb *= instanceColor.rgb;
#endif
#ifdef USE_BATCHING_COLOR
	vColor *= getBatchingColor( getIndirectIndex( gl_DrawID ) );
#endif`,XT=`#define PI 3.141592653589793
#define PI2 6.283185307179586
#define PI_HALF 1.5707963267948966
#define RECIPROCAL_PI 0.3183098861837907
#define RECIPROCAL_PI2 0.15915494309189535
#define EPSILON 1e-6
#ifndef saturate
#define saturate( a ) clamp( a, 0.0, 1.0 )
#endif
#define whiteComplement( a ) ( 1.0 - saturate( a ) )
float pow2( const in float x ) { return x*x; }
vec3 pow2( const in vec3 x ) { return x*x; }
float pow3( const in float x ) { return x*x*x; }
float pow4( const in float x ) { float x2 = x*x; return x2*x2; }
float max3( const in vec3 v ) { return max( max( v.x, v.y ), v.z ); }
float average( const in vec3 v ) { return dot( v, vec3( 0.3333333 ) ); }
highp float rand( const in vec2 uv ) {
	const highp float a = 12.9898, b = 78.233, c = 43758.5453;
	highp float dt = dot( uv.xy, vec2( a,b ) ), sn = mod( dt, PI );
	return fract( sin( sn ) * c );
}
#ifdef HIGH_PRECISION
	float precisionSafeLength( vec3 v ) { return length( v ); }
#else
	float precisionSafeLength( vec3 v ) {
		float maxComponent = max3( abs( v ) );
		return length( v / maxComponent ) * maxComponent;
	}
#endif
struct IncidentLight {
	vec3 color;
	vec3 direction;
	bool visible;
};
struct ReflectedLight {
	vec3 directDiffuse;
	vec3 directSpecular;
	vec3 indirectDiffuse;
	vec3 indirectSpecular;
};
#ifdef USE_ALPHAHASH
	varying vec3 vPosition;
#endif
vec3 transformDirection( in vec3 dir, in mat4 matrix ) {
	return normalize( ( matrix * vec4( dir, 0.0 ) ).xyz );
}
#define inverseTransformDirection transformDirectionByInverseViewMatrix
vec3 transformNormalByInverseViewMatrix( in vec3 normal, in mat4 viewMatrix ) {
	return normalize( ( vec4( normal, 0.0 ) * viewMatrix ).xyz );
}
vec3 transformDirectionByInverseViewMatrix( in vec3 dir, in mat4 viewMatrix ) {
	return normalize( ( vec4( dir, 0.0 ) * viewMatrix ).xyz );
}
bool isPerspectiveMatrix( mat4 m ) {
	return m[ 2 ][ 3 ] == - 1.0;
}
vec2 equirectUv( in vec3 dir ) {
	float u = atan( dir.z, dir.x ) * RECIPROCAL_PI2 + 0.5;
	float v = asin( clamp( dir.y, - 1.0, 1.0 ) ) * RECIPROCAL_PI + 0.5;
	return vec2( u, v );
}
vec3 BRDF_Lambert( const in vec3 diffuseColor ) {
	return RECIPROCAL_PI * diffuseColor;
}
vec3 F_Schlick( const in vec3 f0, const in float f90, const in float dotVH ) {
	float fresnel = exp2( ( - 5.55473 * dotVH - 6.98316 ) * dotVH );
	return f0 * ( 1.0 - fresnel ) + ( f90 * fresnel );
}
float F_Schlick( const in float f0, const in float f90, const in float dotVH ) {
	float fresnel = exp2( ( - 5.55473 * dotVH - 6.98316 ) * dotVH );
	return f0 * ( 1.0 - fresnel ) + ( f90 * fresnel );
} // validated`,YT=`vec3 transformedNormal = objectNormal;
#ifdef USE_TANGENT
	vec3 transformedTangent = objectTangent;
#endif
#ifdef USE_BATCHING
	mat3 bm = mat3( batchingMatrix );
	transformedNormal /= vec3( dot( bm[ 0 ], bm[ 0 ] ), dot( bm[ 1 ], bm[ 1 ] ), dot( bm[ 2 ], bm[ 2 ] ) );
	transformedNormal = bm * transformedNormal;
	#ifdef USE_TANGENT
		transformedTangent = bm * transformedTangent;
	#endif
#endif
#ifdef USE_INSTANCING
	mat3 im = mat3( instanceMatrix );
	transformedNormal /= vec3( dot( im[ 0 ], im[ 0 ] ), dot( im[ 1 ], im[ 1 ] ), dot( im[ 2 ], im[ 2 ] ) );
	transformedNormal = im * transformedNormal;
	#ifdef USE_TANGENT
		transformedTangent = im * transformedTangent;
	#endif
#endif
transformedNormal = normalMatrix * transformedNormal;
#ifdef FLIP_SIDED
	transformedNormal = - transformedNormal;
#endif
#ifdef USE_TANGENT
	transformedTangent = ( modelViewMatrix * vec4( transformedTangent, 0.0 ) ).xyz;
#endif`,ZT=`#ifdef USE_DISPLACEMENTMAP
	uniform sampler2D displacementMap;
	uniform float displacementScale;
	uniform float displacementBias;
#endif`,KT=`#ifdef USE_DISPLACEMENTMAP
	transformed += normalize( objectNormal ) * ( texture2D( displacementMap, vDisplacementMapUv ).x * displacementScale + displacementBias );
#endif`,$T=`#ifdef USE_EMISSIVEMAP
	vec4 emissiveColor = texture2D( emissiveMap, vEmissiveMapUv );
	#ifdef DECODE_VIDEO_TEXTURE_EMISSIVE
		emissiveColor = sRGBTransferEOTF( emissiveColor );
	#endif
	totalEmissiveRadiance *= emissiveColor.rgb;
#endif`,qT=`#ifdef USE_EMISSIVEMAP
	uniform sampler2D emissiveMap;
#endif`,JT="gl_FragColor = linearToOutputTexel( gl_FragColor );",jT=`vec4 LinearTransferOETF( in vec4 value ) {
	return value;
}
vec4 sRGBTransferEOTF( in vec4 value ) {
	return vec4( mix( pow( value.rgb * 0.9478672986 + vec3( 0.0521327014 ), vec3( 2.4 ) ), value.rgb * 0.0773993808, vec3( lessThanEqual( value.rgb, vec3( 0.04045 ) ) ) ), value.a );
}
vec4 sRGBTransferOETF( in vec4 value ) {
	return vec4( mix( pow( value.rgb, vec3( 0.41666 ) ) * 1.055 - vec3( 0.055 ), value.rgb * 12.92, vec3( lessThanEqual( value.rgb, vec3( 0.0031308 ) ) ) ), value.a );
}`,QT=`#ifdef USE_ENVMAP
	#ifdef ENV_WORLDPOS
		vec3 cameraToFrag;
		if ( isOrthographic ) {
			cameraToFrag = normalize( vec3( - viewMatrix[ 0 ][ 2 ], - viewMatrix[ 1 ][ 2 ], - viewMatrix[ 2 ][ 2 ] ) );
		} else {
			cameraToFrag = normalize( vWorldPosition - cameraPosition );
		}
		vec3 worldNormal = transformNormalByInverseViewMatrix( normal, viewMatrix );
		#ifdef ENVMAP_MODE_REFLECTION
			vec3 reflectVec = reflect( cameraToFrag, worldNormal );
		#else
			vec3 reflectVec = refract( cameraToFrag, worldNormal, refractionRatio );
		#endif
	#else
		vec3 reflectVec = vReflect;
	#endif
	#ifdef ENVMAP_TYPE_CUBE
		vec4 envColor = textureCube( envMap, envMapRotation * reflectVec );
		#ifdef ENVMAP_BLENDING_MULTIPLY
			outgoingLight = mix( outgoingLight, outgoingLight * envColor.xyz, specularStrength * reflectivity );
		#elif defined( ENVMAP_BLENDING_MIX )
			outgoingLight = mix( outgoingLight, envColor.xyz, specularStrength * reflectivity );
		#elif defined( ENVMAP_BLENDING_ADD )
			outgoingLight += envColor.xyz * specularStrength * reflectivity;
		#endif
	#endif
#endif`,eR=`#ifdef USE_ENVMAP
	uniform float envMapIntensity;
	uniform mat3 envMapRotation;
	uniform samplerCube envMap;
	#ifdef ENVMAP_TYPE_PMREM
		float roughnessToMip( const in float roughness ) {
			float r = clamp( roughness, 0.0, 1.0 );
			return ENVMAP_MAX_LOD * r * ( 2.0 - r );
		}
	#endif
#endif`,tR=`#ifdef USE_ENVMAP
	uniform float reflectivity;
	#if defined( USE_BUMPMAP ) || defined( USE_NORMALMAP ) || defined( PHONG ) || defined( LAMBERT )
		#define ENV_WORLDPOS
	#endif
	#ifdef ENV_WORLDPOS
		varying vec3 vWorldPosition;
		uniform float refractionRatio;
	#else
		varying vec3 vReflect;
	#endif
#endif`,nR=`#ifdef USE_ENVMAP
	#if defined( USE_BUMPMAP ) || defined( USE_NORMALMAP ) || defined( PHONG ) || defined( LAMBERT )
		#define ENV_WORLDPOS
	#endif
	#ifdef ENV_WORLDPOS
		
		varying vec3 vWorldPosition;
	#else
		varying vec3 vReflect;
		uniform float refractionRatio;
	#endif
#endif`,iR=`#ifdef USE_ENVMAP
	#ifdef ENV_WORLDPOS
		vWorldPosition = worldPosition.xyz;
	#else
		vec3 cameraToVertex;
		if ( isOrthographic ) {
			cameraToVertex = normalize( vec3( - viewMatrix[ 0 ][ 2 ], - viewMatrix[ 1 ][ 2 ], - viewMatrix[ 2 ][ 2 ] ) );
		} else {
			cameraToVertex = normalize( worldPosition.xyz - cameraPosition );
		}
		vec3 worldNormal = transformNormalByInverseViewMatrix( transformedNormal, viewMatrix );
		#ifdef ENVMAP_MODE_REFLECTION
			vReflect = reflect( cameraToVertex, worldNormal );
		#else
			vReflect = refract( cameraToVertex, worldNormal, refractionRatio );
		#endif
	#endif
#endif`,rR=`#ifdef USE_FOG
	vFogDepth = - mvPosition.z;
#endif`,sR=`#ifdef USE_FOG
	varying float vFogDepth;
#endif`,oR=`#ifdef USE_FOG
	#ifdef FOG_EXP2
		float fogFactor = 1.0 - exp( - fogDensity * fogDensity * vFogDepth * vFogDepth );
	#else
		float fogFactor = smoothstep( fogNear, fogFar, vFogDepth );
	#endif
	gl_FragColor.rgb = mix( gl_FragColor.rgb, fogColor, fogFactor );
#endif`,aR=`#ifdef USE_FOG
	uniform vec3 fogColor;
	varying float vFogDepth;
	#ifdef FOG_EXP2
		uniform float fogDensity;
	#else
		uniform float fogNear;
		uniform float fogFar;
	#endif
#endif`,lR=`#ifdef USE_GRADIENTMAP
	uniform sampler2D gradientMap;
#endif
vec3 getGradientIrradiance( vec3 normal, vec3 lightDirection ) {
	float dotNL = dot( normal, lightDirection );
	vec2 coord = vec2( dotNL * 0.5 + 0.5, 0.0 );
	#ifdef USE_GRADIENTMAP
		return vec3( texture2D( gradientMap, coord ).r );
	#else
		vec2 fw = fwidth( coord ) * 0.5;
		return mix( vec3( 0.7 ), vec3( 1.0 ), smoothstep( 0.7 - fw.x, 0.7 + fw.x, coord.x ) );
	#endif
}`,cR=`#ifdef USE_LIGHTMAP
	uniform sampler2D lightMap;
	uniform float lightMapIntensity;
#endif`,uR=`LambertMaterial material;
material.diffuseColor = diffuseColor.rgb;
material.specularStrength = specularStrength;`,hR=`varying vec3 vViewPosition;
struct LambertMaterial {
	vec3 diffuseColor;
	float specularStrength;
};
void RE_Direct_Lambert( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in LambertMaterial material, inout ReflectedLight reflectedLight ) {
	float dotNL = saturate( dot( geometryNormal, directLight.direction ) );
	vec3 irradiance = dotNL * directLight.color;
	reflectedLight.directDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
void RE_IndirectDiffuse_Lambert( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in LambertMaterial material, inout ReflectedLight reflectedLight ) {
	reflectedLight.indirectDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
#define RE_Direct				RE_Direct_Lambert
#define RE_IndirectDiffuse		RE_IndirectDiffuse_Lambert`,fR=`uniform bool receiveShadow;
uniform vec3 ambientLightColor;
#if defined( USE_LIGHT_PROBES )
	uniform vec3 lightProbe[ 9 ];
#endif
vec3 shGetIrradianceAt( in vec3 normal, in vec3 shCoefficients[ 9 ] ) {
	float x = normal.x, y = normal.y, z = normal.z;
	vec3 result = shCoefficients[ 0 ] * 0.886227;
	result += shCoefficients[ 1 ] * 2.0 * 0.511664 * y;
	result += shCoefficients[ 2 ] * 2.0 * 0.511664 * z;
	result += shCoefficients[ 3 ] * 2.0 * 0.511664 * x;
	result += shCoefficients[ 4 ] * 2.0 * 0.429043 * x * y;
	result += shCoefficients[ 5 ] * 2.0 * 0.429043 * y * z;
	result += shCoefficients[ 6 ] * ( 0.743125 * z * z - 0.247708 );
	result += shCoefficients[ 7 ] * 2.0 * 0.429043 * x * z;
	result += shCoefficients[ 8 ] * 0.429043 * ( x * x - y * y );
	return result;
}
vec3 getLightProbeIrradiance( const in vec3 lightProbe[ 9 ], const in vec3 normal ) {
	vec3 worldNormal = transformNormalByInverseViewMatrix( normal, viewMatrix );
	vec3 irradiance = shGetIrradianceAt( worldNormal, lightProbe );
	return irradiance;
}
vec3 getAmbientLightIrradiance( const in vec3 ambientLightColor ) {
	vec3 irradiance = ambientLightColor;
	return irradiance;
}
float getDistanceAttenuation( const in float lightDistance, const in float cutoffDistance, const in float decayExponent ) {
	float distanceFalloff = 1.0 / max( pow( lightDistance, decayExponent ), 0.01 );
	if ( cutoffDistance > 0.0 ) {
		distanceFalloff *= pow2( saturate( 1.0 - pow4( lightDistance / cutoffDistance ) ) );
	}
	return distanceFalloff;
}
float getSpotAttenuation( const in float coneCosine, const in float penumbraCosine, const in float angleCosine ) {
	return smoothstep( coneCosine, penumbraCosine, angleCosine );
}
#if NUM_SUN_LIGHTS > 0
	struct SunLight {
		vec3 direction;
		vec3 color;
	};
	uniform SunLight sunLights[ NUM_SUN_LIGHTS ];
	void getSunLightInfo( const in SunLight sunLight, out IncidentLight light ) {
		light.color = sunLight.color;
		light.direction = sunLight.direction;
		light.visible = true;
	}
#endif
#if NUM_DIR_LIGHTS > 0
	struct DirectionalLight {
		vec3 direction;
		vec3 color;
	};
	uniform DirectionalLight directionalLights[ NUM_DIR_LIGHTS ];
	void getDirectionalLightInfo( const in DirectionalLight directionalLight, out IncidentLight light ) {
		light.color = directionalLight.color;
		light.direction = directionalLight.direction;
		light.visible = true;
	}
#endif
#if NUM_POINT_LIGHTS > 0
	struct PointLight {
		vec3 position;
		vec3 color;
		float distance;
		float decay;
	};
	uniform PointLight pointLights[ NUM_POINT_LIGHTS ];
	void getPointLightInfo( const in PointLight pointLight, const in vec3 geometryPosition, out IncidentLight light ) {
		vec3 lVector = pointLight.position - geometryPosition;
		light.direction = normalize( lVector );
		float lightDistance = length( lVector );
		light.color = pointLight.color;
		light.color *= getDistanceAttenuation( lightDistance, pointLight.distance, pointLight.decay );
		light.visible = ( light.color != vec3( 0.0 ) );
	}
#endif
#if NUM_SPOT_LIGHTS > 0
	struct SpotLight {
		vec3 position;
		vec3 direction;
		vec3 color;
		float distance;
		float decay;
		float coneCos;
		float penumbraCos;
	};
	uniform SpotLight spotLights[ NUM_SPOT_LIGHTS ];
	void getSpotLightInfo( const in SpotLight spotLight, const in vec3 geometryPosition, out IncidentLight light ) {
		vec3 lVector = spotLight.position - geometryPosition;
		light.direction = normalize( lVector );
		float angleCos = dot( light.direction, spotLight.direction );
		float spotAttenuation = getSpotAttenuation( spotLight.coneCos, spotLight.penumbraCos, angleCos );
		if ( spotAttenuation > 0.0 ) {
			float lightDistance = length( lVector );
			light.color = spotLight.color * spotAttenuation;
			light.color *= getDistanceAttenuation( lightDistance, spotLight.distance, spotLight.decay );
			light.visible = ( light.color != vec3( 0.0 ) );
		} else {
			light.color = vec3( 0.0 );
			light.visible = false;
		}
	}
#endif
#if NUM_RECT_AREA_LIGHTS > 0
	struct RectAreaLight {
		vec3 color;
		vec3 position;
		vec3 halfWidth;
		vec3 halfHeight;
	};
	uniform sampler2D ltc_1;	uniform sampler2D ltc_2;
	uniform RectAreaLight rectAreaLights[ NUM_RECT_AREA_LIGHTS ];
#endif
#if NUM_HEMI_LIGHTS > 0
	struct HemisphereLight {
		vec3 direction;
		vec3 skyColor;
		vec3 groundColor;
	};
	uniform HemisphereLight hemisphereLights[ NUM_HEMI_LIGHTS ];
	vec3 getHemisphereLightIrradiance( const in HemisphereLight hemiLight, const in vec3 normal ) {
		float dotNL = dot( normal, hemiLight.direction );
		float hemiDiffuseWeight = 0.5 * dotNL + 0.5;
		vec3 irradiance = mix( hemiLight.groundColor, hemiLight.skyColor, hemiDiffuseWeight );
		return irradiance;
	}
#endif
#include <lightprobes_pars_fragment>`,dR=`#ifdef USE_ENVMAP
	vec3 getIBLIrradiance( const in vec3 normal ) {
		#ifdef ENVMAP_TYPE_PMREM
			vec3 worldNormal = transformNormalByInverseViewMatrix( normal, viewMatrix );
			vec4 envMapColor = textureLod( envMap, envMapRotation * worldNormal, ENVMAP_MAX_LOD );
			return PI * envMapColor.rgb * envMapIntensity;
		#else
			return vec3( 0.0 );
		#endif
	}
	vec3 getIBLRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness ) {
		#ifdef ENVMAP_TYPE_PMREM
			vec3 reflectVec = reflect( - viewDir, normal );
			reflectVec = normalize( mix( reflectVec, normal, pow4( roughness ) ) );
			reflectVec = transformDirectionByInverseViewMatrix( reflectVec, viewMatrix );
			vec4 envMapColor = textureLod( envMap, envMapRotation * reflectVec, roughnessToMip( roughness ) );
			return envMapColor.rgb * envMapIntensity;
		#else
			return vec3( 0.0 );
		#endif
	}
	#ifdef USE_RETROREFLECTION
		vec3 getIBLRetroRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness ) {
			#ifdef ENVMAP_TYPE_PMREM
				vec3 retroVec = normalize( mix( viewDir, normal, pow4( roughness ) ) );
				retroVec = transformDirectionByInverseViewMatrix( retroVec, viewMatrix );
				vec4 envMapColor = textureLod( envMap, envMapRotation * retroVec, roughnessToMip( roughness ) );
				return envMapColor.rgb * envMapIntensity;
			#else
				return vec3( 0.0 );
			#endif
		}
	#endif
	#ifdef USE_ANISOTROPY
		vec3 getIBLAnisotropyRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness, const in vec3 bitangent, const in float anisotropy ) {
			#ifdef ENVMAP_TYPE_PMREM
				vec3 bentNormal = cross( bitangent, viewDir );
				bentNormal = normalize( cross( bentNormal, bitangent ) );
				bentNormal = normalize( mix( bentNormal, normal, pow2( pow2( 1.0 - anisotropy * ( 1.0 - roughness ) ) ) ) );
				return getIBLRadiance( viewDir, bentNormal, roughness );
			#else
				return vec3( 0.0 );
			#endif
		}
		#ifdef USE_RETROREFLECTION
			vec3 getIBLAnisotropyRetroRadiance( const in vec3 viewDir, const in vec3 normal, const in float roughness, const in vec3 bitangent, const in float anisotropy ) {
				#ifdef ENVMAP_TYPE_PMREM
					vec3 bentNormal = cross( bitangent, viewDir );
					bentNormal = normalize( cross( bentNormal, bitangent ) );
					bentNormal = normalize( mix( bentNormal, normal, pow2( pow2( 1.0 - anisotropy * ( 1.0 - roughness ) ) ) ) );
					return getIBLRetroRadiance( viewDir, bentNormal, roughness );
				#else
					return vec3( 0.0 );
				#endif
			}
		#endif
	#endif
#endif`,pR=`ToonMaterial material;
material.diffuseColor = diffuseColor.rgb;`,mR=`varying vec3 vViewPosition;
struct ToonMaterial {
	vec3 diffuseColor;
};
void RE_Direct_Toon( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in ToonMaterial material, inout ReflectedLight reflectedLight ) {
	vec3 irradiance = getGradientIrradiance( geometryNormal, directLight.direction ) * directLight.color;
	reflectedLight.directDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
void RE_IndirectDiffuse_Toon( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in ToonMaterial material, inout ReflectedLight reflectedLight ) {
	reflectedLight.indirectDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
#define RE_Direct				RE_Direct_Toon
#define RE_IndirectDiffuse		RE_IndirectDiffuse_Toon`,gR=`BlinnPhongMaterial material;
material.diffuseColor = diffuseColor.rgb;
material.specularColor = specular;
material.specularShininess = shininess;
material.specularStrength = specularStrength;`,yR=`varying vec3 vViewPosition;
struct BlinnPhongMaterial {
	vec3 diffuseColor;
	vec3 specularColor;
	float specularShininess;
	float specularStrength;
};
void RE_Direct_BlinnPhong( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in BlinnPhongMaterial material, inout ReflectedLight reflectedLight ) {
	float dotNL = saturate( dot( geometryNormal, directLight.direction ) );
	vec3 irradiance = dotNL * directLight.color;
	reflectedLight.directDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
	reflectedLight.directSpecular += irradiance * BRDF_BlinnPhong( directLight.direction, geometryViewDir, geometryNormal, material.specularColor, material.specularShininess ) * material.specularStrength;
}
void RE_IndirectDiffuse_BlinnPhong( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in BlinnPhongMaterial material, inout ReflectedLight reflectedLight ) {
	reflectedLight.indirectDiffuse += irradiance * BRDF_Lambert( material.diffuseColor );
}
#define RE_Direct				RE_Direct_BlinnPhong
#define RE_IndirectDiffuse		RE_IndirectDiffuse_BlinnPhong`,_R=`PhysicalMaterial material;
material.diffuseColor = diffuseColor.rgb;
material.diffuseContribution = diffuseColor.rgb * ( 1.0 - metalnessFactor );
material.metalness = metalnessFactor;
vec3 dxy = max( abs( dFdx( nonPerturbedNormal ) ), abs( dFdy( nonPerturbedNormal ) ) );
float geometryRoughness = max( max( dxy.x, dxy.y ), dxy.z );
material.roughness = max( roughnessFactor, 0.045 );
material.roughness += geometryRoughness;
material.roughness = min( material.roughness, 1.0 );
#ifdef USE_DIFFUSE_ROUGHNESS
	float diffuseRoughnessFactor = diffuseRoughness;
	#ifdef USE_DIFFUSE_ROUGHNESSMAP
		diffuseRoughnessFactor *= texture2D( diffuseRoughnessMap, vDiffuseRoughnessMapUv ).r;
	#endif
	material.diffuseRoughness = saturate( diffuseRoughnessFactor );
#endif
#ifdef IOR
	material.ior = ior;
	#ifdef USE_SPECULAR
		float specularIntensityFactor = specularIntensity;
		vec3 specularColorFactor = specularColor;
		#ifdef USE_SPECULAR_COLORMAP
			specularColorFactor *= texture2D( specularColorMap, vSpecularColorMapUv ).rgb;
		#endif
		#ifdef USE_SPECULAR_INTENSITYMAP
			specularIntensityFactor *= texture2D( specularIntensityMap, vSpecularIntensityMapUv ).a;
		#endif
		material.specularF90 = mix( specularIntensityFactor, 1.0, metalnessFactor );
	#else
		float specularIntensityFactor = 1.0;
		vec3 specularColorFactor = vec3( 1.0 );
		material.specularF90 = 1.0;
	#endif
	material.specularColor = min( pow2( ( material.ior - 1.0 ) / ( material.ior + 1.0 ) ) * specularColorFactor, vec3( 1.0 ) ) * specularIntensityFactor;
	material.specularColorBlended = mix( material.specularColor, diffuseColor.rgb, metalnessFactor );
#else
	material.specularColor = vec3( 0.04 );
	material.specularColorBlended = mix( material.specularColor, diffuseColor.rgb, metalnessFactor );
	material.specularF90 = 1.0;
#endif
#ifdef USE_CLEARCOAT
	material.clearcoat = clearcoat;
	material.clearcoatRoughness = clearcoatRoughness;
	material.clearcoatF0 = vec3( 0.04 );
	material.clearcoatF90 = 1.0;
	#ifdef USE_CLEARCOATMAP
		material.clearcoat *= texture2D( clearcoatMap, vClearcoatMapUv ).x;
	#endif
	#ifdef USE_CLEARCOAT_ROUGHNESSMAP
		material.clearcoatRoughness *= texture2D( clearcoatRoughnessMap, vClearcoatRoughnessMapUv ).y;
	#endif
	material.clearcoat = saturate( material.clearcoat );	material.clearcoatRoughness = max( material.clearcoatRoughness, 0.045 );
	material.clearcoatRoughness += geometryRoughness;
	material.clearcoatRoughness = min( material.clearcoatRoughness, 1.0 );
#endif
#ifdef USE_DISPERSION
	material.dispersion = dispersion;
#endif
#ifdef USE_RETROREFLECTION
	material.retroreflectivity = retroreflectivity;
#endif
#ifdef USE_IRIDESCENCE
	material.iridescence = iridescence;
	material.iridescenceIOR = iridescenceIOR;
	#ifdef USE_IRIDESCENCEMAP
		material.iridescence *= texture2D( iridescenceMap, vIridescenceMapUv ).r;
	#endif
	#ifdef USE_IRIDESCENCE_THICKNESSMAP
		material.iridescenceThickness = (iridescenceThicknessMaximum - iridescenceThicknessMinimum) * texture2D( iridescenceThicknessMap, vIridescenceThicknessMapUv ).g + iridescenceThicknessMinimum;
	#else
		material.iridescenceThickness = iridescenceThicknessMaximum;
	#endif
#endif
#ifdef USE_SHEEN
	material.sheenColor = sheenColor;
	#ifdef USE_SHEEN_COLORMAP
		material.sheenColor *= texture2D( sheenColorMap, vSheenColorMapUv ).rgb;
	#endif
	material.sheenRoughness = clamp( sheenRoughness, 0.0001, 1.0 );
	#ifdef USE_SHEEN_ROUGHNESSMAP
		material.sheenRoughness *= texture2D( sheenRoughnessMap, vSheenRoughnessMapUv ).a;
	#endif
#endif
#ifdef USE_ANISOTROPY
	#ifdef USE_ANISOTROPYMAP
		mat2 anisotropyMat = mat2( anisotropyVector.x, anisotropyVector.y, - anisotropyVector.y, anisotropyVector.x );
		vec3 anisotropyPolar = texture2D( anisotropyMap, vAnisotropyMapUv ).rgb;
		vec2 anisotropyV = anisotropyMat * normalize( 2.0 * anisotropyPolar.rg - vec2( 1.0 ) ) * anisotropyPolar.b;
	#else
		vec2 anisotropyV = anisotropyVector;
	#endif
	material.anisotropy = length( anisotropyV );
	if( material.anisotropy == 0.0 ) {
		anisotropyV = vec2( 1.0, 0.0 );
	} else {
		anisotropyV /= material.anisotropy;
		material.anisotropy = saturate( material.anisotropy );
	}
	material.alphaT = mix( pow2( material.roughness ), 1.0, pow2( material.anisotropy ) );
	material.anisotropyT = tbn[ 0 ] * anisotropyV.x + tbn[ 1 ] * anisotropyV.y;
	material.anisotropyB = tbn[ 1 ] * anisotropyV.x - tbn[ 0 ] * anisotropyV.y;
#endif`,xR=`uniform sampler2D dfgLUT;
struct PhysicalMaterial {
	vec3 diffuseColor;
	vec3 diffuseContribution;
	vec3 specularColor;
	vec3 specularColorBlended;
	float roughness;
	float metalness;
	float specularF90;
	float dispersion;
	vec2 dfg;
	vec3 multiScatteringCompensation;
	#ifdef USE_DIFFUSE_ROUGHNESS
		float diffuseRoughness;
	#endif
	#ifdef USE_RETROREFLECTION
		float retroreflectivity;
	#endif
	#ifdef USE_CLEARCOAT
		float clearcoat;
		float clearcoatRoughness;
		vec3 clearcoatF0;
		float clearcoatF90;
	#endif
	#ifdef USE_IRIDESCENCE
		float iridescence;
		float iridescenceIOR;
		float iridescenceThickness;
		vec3 iridescenceFresnel;
		vec3 iridescenceF0Dielectric;
		vec3 iridescenceF0Metallic;
	#endif
	#ifdef USE_SHEEN
		vec3 sheenColor;
		float sheenRoughness;
	#endif
	#ifdef IOR
		float ior;
	#endif
	#ifdef USE_TRANSMISSION
		float transmission;
		float transmissionAlpha;
		float thickness;
		float attenuationDistance;
		vec3 attenuationColor;
	#endif
	#ifdef USE_ANISOTROPY
		float anisotropy;
		float alphaT;
		vec3 anisotropyT;
		vec3 anisotropyB;
	#endif
};
vec3 clearcoatSpecularDirect = vec3( 0.0 );
vec3 clearcoatSpecularIndirect = vec3( 0.0 );
vec3 sheenSpecularDirect = vec3( 0.0 );
vec3 sheenSpecularIndirect = vec3(0.0 );
vec3 Schlick_to_F0( const in vec3 f, const in float f90, const in float dotVH ) {
    float x = clamp( 1.0 - dotVH, 0.0, 1.0 );
    float x2 = x * x;
    float x5 = clamp( x * x2 * x2, 0.0, 0.9999 );
    return ( f - vec3( f90 ) * x5 ) / ( 1.0 - x5 );
}
#ifdef USE_DIFFUSE_ROUGHNESS
	const float EON_EPSILON = 1e-7;
	float FON_DirectionalAlbedo( const in float mu, const in float roughness, const in float A ) {
		float muComp = 1.0 - mu;
		float gOverPi = muComp * ( 0.0571085289 + muComp * ( 0.491881867 + muComp * ( - 0.332181442 + muComp * 0.0714429953 ) ) );
		return A * ( 1.0 + roughness * gOverPi );
	}
	vec3 BRDF_EON( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in vec3 diffuseColor, const in float roughness ) {
		vec3 rho = saturate( diffuseColor );
		if ( roughness <= EON_EPSILON ) return BRDF_Lambert( rho );
		float dotNL = saturate( dot( normal, lightDir ) );
		float dotNV = saturate( dot( normal, viewDir ) );
		float s = dot( lightDir, viewDir ) - dotNL * dotNV;
		float sOverT = ( s > 0.0 ) ? s / max( max( dotNL, dotNV ), EON_EPSILON ) : s;
		float A = 1.0 / ( 1.0 + ( 0.5 - 2.0 / ( 3.0 * PI ) ) * roughness );
		vec3 singleScatter = rho * RECIPROCAL_PI * A * ( 1.0 + roughness * sOverT );
		float averageAlbedo = A * ( 1.0 + ( 2.0 / 3.0 - 28.0 / ( 15.0 * PI ) ) * roughness );
		float albedoV = FON_DirectionalAlbedo( dotNV, roughness, A );
		float albedoL = FON_DirectionalAlbedo( dotNL, roughness, A );
		vec3 rhoMultiScatter = rho * rho * averageAlbedo / max( vec3( EON_EPSILON ), vec3( 1.0 ) - rho * ( 1.0 - averageAlbedo ) );
		vec3 multiScatter = rhoMultiScatter * RECIPROCAL_PI
			* max( EON_EPSILON, 1.0 - albedoV )
			* max( EON_EPSILON, 1.0 - albedoL )
			/ max( EON_EPSILON, 1.0 - averageAlbedo );
		return singleScatter + multiScatter;
	}
	vec3 EON_DirectionalAlbedo( const in vec3 diffuseColor, const in float roughness, const in float dotNV ) {
		vec3 rho = saturate( diffuseColor );
		if ( roughness <= EON_EPSILON ) return rho;
		float A = 1.0 / ( 1.0 + ( 0.5 - 2.0 / ( 3.0 * PI ) ) * roughness );
		float directionalAlbedo = FON_DirectionalAlbedo( dotNV, roughness, A );
		float averageAlbedo = A * ( 1.0 + ( 2.0 / 3.0 - 28.0 / ( 15.0 * PI ) ) * roughness );
		vec3 rhoMultiScatter = rho * rho * averageAlbedo / max( vec3( EON_EPSILON ), vec3( 1.0 ) - rho * ( 1.0 - averageAlbedo ) );
		return rho * directionalAlbedo + rhoMultiScatter * ( 1.0 - directionalAlbedo );
	}
#endif
float V_GGX_SmithCorrelated( const in float alpha, const in float dotNL, const in float dotNV ) {
	float a2 = pow2( alpha );
	float gv = dotNL * sqrt( a2 + ( 1.0 - a2 ) * pow2( dotNV ) );
	float gl = dotNV * sqrt( a2 + ( 1.0 - a2 ) * pow2( dotNL ) );
	return 0.5 / max( gv + gl, EPSILON );
}
float D_GGX( const in float alpha, const in float dotNH ) {
	float a2 = pow2( alpha );
	float denom = pow2( dotNH ) * ( a2 - 1.0 ) + 1.0;
	return RECIPROCAL_PI * a2 / pow2( denom );
}
#ifdef USE_ANISOTROPY
	float V_GGX_SmithCorrelated_Anisotropic( const in float alphaT, const in float alphaB, const in float dotTV, const in float dotBV, const in float dotTL, const in float dotBL, const in float dotNV, const in float dotNL ) {
		float gv = dotNL * length( vec3( alphaT * dotTV, alphaB * dotBV, dotNV ) );
		float gl = dotNV * length( vec3( alphaT * dotTL, alphaB * dotBL, dotNL ) );
		return 0.5 / max( gv + gl, EPSILON );
	}
	float D_GGX_Anisotropic( const in float alphaT, const in float alphaB, const in float dotNH, const in float dotTH, const in float dotBH ) {
		float a2 = alphaT * alphaB;
		highp vec3 v = vec3( alphaB * dotTH, alphaT * dotBH, a2 * dotNH );
		highp float v2 = dot( v, v );
		float w2 = a2 / v2;
		return RECIPROCAL_PI * a2 * pow2 ( w2 );
	}
#endif
#ifdef USE_CLEARCOAT
	vec3 BRDF_GGX_Clearcoat( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in PhysicalMaterial material) {
		vec3 f0 = material.clearcoatF0;
		float f90 = material.clearcoatF90;
		float roughness = max( material.clearcoatRoughness, 0.045 );
		float alpha = pow2( roughness );
		vec3 halfDir = normalize( lightDir + viewDir );
		float dotNL = saturate( dot( normal, lightDir ) );
		float dotNV = saturate( dot( normal, viewDir ) );
		float dotNH = saturate( dot( normal, halfDir ) );
		float dotVH = saturate( dot( viewDir, halfDir ) );
		vec3 F = F_Schlick( f0, f90, dotVH );
		float V = V_GGX_SmithCorrelated( alpha, dotNL, dotNV );
		float D = D_GGX( alpha, dotNH );
		return F * ( V * D );
	}
#endif
vec3 BRDF_GGX( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, const in PhysicalMaterial material ) {
	vec3 f0 = material.specularColorBlended;
	float f90 = material.specularF90;
	float roughness = max( material.roughness, 0.045 );
	float alpha = pow2( roughness );
	vec3 halfDir = normalize( lightDir + viewDir );
	float dotNL = saturate( dot( normal, lightDir ) );
	float dotNV = saturate( dot( normal, viewDir ) );
	float dotNH = saturate( dot( normal, halfDir ) );
	float dotVH = saturate( dot( viewDir, halfDir ) );
	vec3 F = F_Schlick( f0, f90, dotVH );
	#ifdef USE_IRIDESCENCE
		F = mix( F, material.iridescenceFresnel, material.iridescence );
	#endif
	#ifdef USE_ANISOTROPY
		float dotTL = dot( material.anisotropyT, lightDir );
		float dotTV = dot( material.anisotropyT, viewDir );
		float dotTH = dot( material.anisotropyT, halfDir );
		float dotBL = dot( material.anisotropyB, lightDir );
		float dotBV = dot( material.anisotropyB, viewDir );
		float dotBH = dot( material.anisotropyB, halfDir );
		float alphaT = max( material.alphaT, alpha );
		float V = V_GGX_SmithCorrelated_Anisotropic( alphaT, alpha, dotTV, dotBV, dotTL, dotBL, dotNV, dotNL );
		float D = D_GGX_Anisotropic( alphaT, alpha, dotNH, dotTH, dotBH );
	#else
		float V = V_GGX_SmithCorrelated( alpha, dotNL, dotNV );
		float D = D_GGX( alpha, dotNH );
	#endif
	return F * ( V * D );
}
vec2 LTC_Uv( const in vec3 N, const in vec3 V, const in float roughness ) {
	const float LUT_SIZE = 64.0;
	const float LUT_SCALE = ( LUT_SIZE - 1.0 ) / LUT_SIZE;
	const float LUT_BIAS = 0.5 / LUT_SIZE;
	float dotNV = saturate( dot( N, V ) );
	vec2 uv = vec2( roughness, sqrt( 1.0 - dotNV ) );
	uv = uv * LUT_SCALE + LUT_BIAS;
	return uv;
}
float LTC_ClippedSphereFormFactor( const in vec3 f ) {
	float l = length( f );
	return max( ( l * l + f.z ) / ( l + 1.0 ), 0.0 );
}
vec3 LTC_EdgeVectorFormFactor( const in vec3 v1, const in vec3 v2 ) {
	float x = dot( v1, v2 );
	float y = abs( x );
	float a = 0.8543985 + ( 0.4965155 + 0.0145206 * y ) * y;
	float b = 3.4175940 + ( 4.1616724 + y ) * y;
	float v = a / b;
	float theta_sintheta = ( x > 0.0 ) ? v : 0.5 * inversesqrt( max( 1.0 - x * x, 1e-7 ) ) - v;
	return cross( v1, v2 ) * theta_sintheta;
}
vec3 LTC_Evaluate( const in vec3 N, const in vec3 V, const in vec3 P, const in mat3 mInv, const in vec3 rectCoords[ 4 ] ) {
	vec3 v1 = rectCoords[ 1 ] - rectCoords[ 0 ];
	vec3 v2 = rectCoords[ 3 ] - rectCoords[ 0 ];
	vec3 lightNormal = cross( v1, v2 );
	if( dot( lightNormal, P - rectCoords[ 0 ] ) < 0.0 ) return vec3( 0.0 );
	vec3 T1, T2;
	T1 = normalize( V - N * dot( V, N ) );
	T2 = - cross( N, T1 );
	mat3 mat = mInv * transpose( mat3( T1, T2, N ) );
	vec3 coords[ 4 ];
	coords[ 0 ] = mat * ( rectCoords[ 0 ] - P );
	coords[ 1 ] = mat * ( rectCoords[ 1 ] - P );
	coords[ 2 ] = mat * ( rectCoords[ 2 ] - P );
	coords[ 3 ] = mat * ( rectCoords[ 3 ] - P );
	coords[ 0 ] = normalize( coords[ 0 ] );
	coords[ 1 ] = normalize( coords[ 1 ] );
	coords[ 2 ] = normalize( coords[ 2 ] );
	coords[ 3 ] = normalize( coords[ 3 ] );
	vec3 vectorFormFactor = vec3( 0.0 );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 0 ], coords[ 1 ] );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 1 ], coords[ 2 ] );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 2 ], coords[ 3 ] );
	vectorFormFactor += LTC_EdgeVectorFormFactor( coords[ 3 ], coords[ 0 ] );
	float result = LTC_ClippedSphereFormFactor( vectorFormFactor );
	return vec3( result );
}
#if defined( USE_SHEEN )
float D_Charlie( float roughness, float dotNH ) {
	float alpha = pow2( roughness );
	float invAlpha = 1.0 / alpha;
	float cos2h = dotNH * dotNH;
	float sin2h = max( 1.0 - cos2h, 0.0078125 );
	return ( 2.0 + invAlpha ) * pow( sin2h, invAlpha * 0.5 ) / ( 2.0 * PI );
}
float V_Neubelt( float dotNV, float dotNL ) {
	return saturate( 1.0 / ( 4.0 * ( dotNL + dotNV - dotNL * dotNV ) ) );
}
vec3 BRDF_Sheen( const in vec3 lightDir, const in vec3 viewDir, const in vec3 normal, vec3 sheenColor, const in float sheenRoughness ) {
	vec3 halfDir = normalize( lightDir + viewDir );
	float dotNL = saturate( dot( normal, lightDir ) );
	float dotNV = saturate( dot( normal, viewDir ) );
	float dotNH = saturate( dot( normal, halfDir ) );
	float D = D_Charlie( sheenRoughness, dotNH );
	float V = V_Neubelt( dotNV, dotNL );
	return sheenColor * ( D * V );
}
#endif
float IBLSheenBRDF( const in vec3 normal, const in vec3 viewDir, const in float roughness ) {
	float dotNV = saturate( dot( normal, viewDir ) );
	float r2 = roughness * roughness;
	float rInv = 1.0 / ( roughness + 0.1 );
	float a = -1.9362 + 1.0678 * roughness + 0.4573 * r2 - 0.8469 * rInv;
	float b = -0.6014 + 0.5538 * roughness - 0.4670 * r2 - 0.1255 * rInv;
	float DG = exp( a * dotNV + b );
	return saturate( DG );
}
vec3 EnvironmentBRDF( const in vec3 normal, const in vec3 viewDir, const in vec3 specularColor, const in float specularF90, const in float roughness ) {
	float dotNV = saturate( dot( normal, viewDir ) );
	vec2 fab = texture2D( dfgLUT, vec2( roughness, dotNV ) ).rg;
	return specularColor * fab.x + specularF90 * fab.y;
}
#ifdef USE_IRIDESCENCE
void computeMultiscatteringIridescence( const in vec2 fab, const in vec3 specularColor, const in float specularF90, const in float iridescence, const in vec3 iridescenceF0, inout vec3 singleScatter, inout vec3 multiScatter ) {
#else
void computeMultiscattering( const in vec2 fab, const in vec3 specularColor, const in float specularF90, inout vec3 singleScatter, inout vec3 multiScatter ) {
#endif
	#ifdef USE_IRIDESCENCE
		vec3 Fr = mix( specularColor, iridescenceF0, iridescence );
	#else
		vec3 Fr = specularColor;
	#endif
	vec3 FssEss = Fr * fab.x + specularF90 * fab.y;
	float Ess = fab.x + fab.y;
	float Ems = 1.0 - Ess;
	vec3 Favg = Fr + ( 1.0 - Fr ) * 0.047619;	vec3 Fms = FssEss * Favg / ( 1.0 - Ems * Favg );
	singleScatter += FssEss;
	multiScatter += Fms * Ems;
}
#if NUM_RECT_AREA_LIGHTS > 0
	void RE_Direct_RectArea_Physical( const in RectAreaLight rectAreaLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight ) {
		vec3 normal = geometryNormal;
		vec3 viewDir = geometryViewDir;
		vec3 position = geometryPosition;
		vec3 lightPos = rectAreaLight.position;
		vec3 halfWidth = rectAreaLight.halfWidth;
		vec3 halfHeight = rectAreaLight.halfHeight;
		vec3 lightColor = rectAreaLight.color;
		float roughness = material.roughness;
		vec3 rectCoords[ 4 ];
		rectCoords[ 0 ] = lightPos + halfWidth - halfHeight;		rectCoords[ 1 ] = lightPos - halfWidth - halfHeight;
		rectCoords[ 2 ] = lightPos - halfWidth + halfHeight;
		rectCoords[ 3 ] = lightPos + halfWidth + halfHeight;
		vec2 uv = LTC_Uv( normal, viewDir, roughness );
		vec4 t1 = texture2D( ltc_1, uv );
		vec4 t2 = texture2D( ltc_2, uv );
		mat3 mInv = mat3(
			vec3( t1.x, 0, t1.y ),
			vec3(    0, 1,    0 ),
			vec3( t1.z, 0, t1.w )
		);
		vec3 fresnel = ( material.specularColorBlended * t2.x + ( material.specularF90 - material.specularColorBlended ) * t2.y );
		reflectedLight.directSpecular += lightColor * fresnel * LTC_Evaluate( normal, viewDir, position, mInv, rectCoords );
		reflectedLight.directDiffuse += lightColor * material.diffuseContribution * LTC_Evaluate( normal, viewDir, position, mat3( 1.0 ), rectCoords );
		#ifdef USE_CLEARCOAT
			vec3 Ncc = geometryClearcoatNormal;
			vec2 uvClearcoat = LTC_Uv( Ncc, viewDir, material.clearcoatRoughness );
			vec4 t1Clearcoat = texture2D( ltc_1, uvClearcoat );
			vec4 t2Clearcoat = texture2D( ltc_2, uvClearcoat );
			mat3 mInvClearcoat = mat3(
				vec3( t1Clearcoat.x, 0, t1Clearcoat.y ),
				vec3(             0, 1,             0 ),
				vec3( t1Clearcoat.z, 0, t1Clearcoat.w )
			);
			vec3 fresnelClearcoat = material.clearcoatF0 * t2Clearcoat.x + ( material.clearcoatF90 - material.clearcoatF0 ) * t2Clearcoat.y;
			clearcoatSpecularDirect += lightColor * fresnelClearcoat * LTC_Evaluate( Ncc, viewDir, position, mInvClearcoat, rectCoords );
		#endif
	}
#endif
void RE_Direct_Physical( const in IncidentLight directLight, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight ) {
	float dotNL = saturate( dot( geometryNormal, directLight.direction ) );
	vec3 irradiance = dotNL * directLight.color;
	#ifdef USE_CLEARCOAT
		float dotNLcc = saturate( dot( geometryClearcoatNormal, directLight.direction ) );
		vec3 ccIrradiance = dotNLcc * directLight.color;
		clearcoatSpecularDirect += ccIrradiance * BRDF_GGX_Clearcoat( directLight.direction, geometryViewDir, geometryClearcoatNormal, material );
	#endif
	#ifdef USE_SHEEN
 
 		sheenSpecularDirect += irradiance * BRDF_Sheen( directLight.direction, geometryViewDir, geometryNormal, material.sheenColor, material.sheenRoughness );
 
 		float sheenAlbedoV = IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness );
 		float sheenAlbedoL = IBLSheenBRDF( geometryNormal, directLight.direction, material.sheenRoughness );
 
 		float sheenEnergyComp = 1.0 - max3( material.sheenColor ) * max( sheenAlbedoV, sheenAlbedoL );
 
 		irradiance *= sheenEnergyComp;
 
 	#endif
	vec3 specularBRDF = BRDF_GGX( directLight.direction, geometryViewDir, geometryNormal, material );
	#ifdef USE_RETROREFLECTION
		vec3 retroViewDir = reflect( - geometryViewDir, geometryNormal );
		vec3 retroSpecularBRDF = BRDF_GGX( directLight.direction, retroViewDir, geometryNormal, material );
		specularBRDF = mix( specularBRDF, retroSpecularBRDF, saturate( material.retroreflectivity ) );
	#endif
	reflectedLight.directSpecular += irradiance * specularBRDF * material.multiScatteringCompensation;
	vec3 halfDir = normalize( directLight.direction + geometryViewDir );
	float dotVH = saturate( dot( geometryViewDir, halfDir ) );
	vec3 F = F_Schlick( material.specularColor, material.specularF90, dotVH );
	#ifdef USE_RETROREFLECTION
		vec3 retroHalfDir = normalize( directLight.direction + retroViewDir );
		float dotRetroVH = saturate( dot( retroViewDir, retroHalfDir ) );
		vec3 retroF = F_Schlick( material.specularColor, material.specularF90, dotRetroVH );
		F = mix( F, retroF, saturate( material.retroreflectivity ) );
	#endif
	#ifdef USE_DIFFUSE_ROUGHNESS
		vec3 diffuseBRDF = BRDF_EON( directLight.direction, geometryViewDir, geometryNormal, material.diffuseColor, material.diffuseRoughness ) * ( 1.0 - material.metalness );
	#else
		vec3 diffuseBRDF = BRDF_Lambert( material.diffuseContribution );
	#endif
	reflectedLight.directDiffuse += irradiance * diffuseBRDF * ( 1.0 - F );
}
void RE_IndirectDiffuse_Physical( const in vec3 irradiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight ) {
	vec3 singleScattering = vec3( 0.0 );
	vec3 multiScattering = vec3( 0.0 );
	#ifdef USE_IRIDESCENCE
		computeMultiscatteringIridescence( material.dfg, material.specularColor, material.specularF90, material.iridescence, material.iridescenceF0Dielectric, singleScattering, multiScattering );
	#else
		computeMultiscattering( material.dfg, material.specularColor, material.specularF90, singleScattering, multiScattering );
	#endif
	#ifdef USE_DIFFUSE_ROUGHNESS
		float dotNV = saturate( dot( geometryNormal, geometryViewDir ) );
		vec3 diffuseAlbedo = EON_DirectionalAlbedo( material.diffuseColor, material.diffuseRoughness, dotNV ) * ( 1.0 - material.metalness );
		vec3 diffuse = irradiance * RECIPROCAL_PI * diffuseAlbedo * ( 1.0 - singleScattering - multiScattering );
	#else
		vec3 diffuse = irradiance * BRDF_Lambert( material.diffuseContribution ) * ( 1.0 - singleScattering - multiScattering );
	#endif
	#ifdef USE_SHEEN
		float sheenAlbedo = IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness );
		sheenSpecularIndirect += irradiance * material.sheenColor * sheenAlbedo * RECIPROCAL_PI;
		float sheenEnergyComp = 1.0 - max3( material.sheenColor ) * sheenAlbedo;
		diffuse *= sheenEnergyComp;
	#endif
	reflectedLight.indirectDiffuse += diffuse;
}
void RE_IndirectSpecular_Physical( const in vec3 radiance, const in vec3 irradiance, const in vec3 clearcoatRadiance, const in vec3 geometryPosition, const in vec3 geometryNormal, const in vec3 geometryViewDir, const in vec3 geometryClearcoatNormal, const in PhysicalMaterial material, inout ReflectedLight reflectedLight) {
	#ifdef USE_CLEARCOAT
		clearcoatSpecularIndirect += clearcoatRadiance * EnvironmentBRDF( geometryClearcoatNormal, geometryViewDir, material.clearcoatF0, material.clearcoatF90, material.clearcoatRoughness );
	#endif
	#ifdef USE_SHEEN
		sheenSpecularIndirect += irradiance * material.sheenColor * IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness ) * RECIPROCAL_PI;
 	#endif
	vec3 singleScatteringDielectric = vec3( 0.0 );
	vec3 multiScatteringDielectric = vec3( 0.0 );
	vec3 singleScatteringMetallic = vec3( 0.0 );
	vec3 multiScatteringMetallic = vec3( 0.0 );
	#ifdef USE_IRIDESCENCE
		computeMultiscatteringIridescence( material.dfg, material.specularColor, material.specularF90, material.iridescence, material.iridescenceF0Dielectric, singleScatteringDielectric, multiScatteringDielectric );
		computeMultiscatteringIridescence( material.dfg, material.diffuseColor, material.specularF90, material.iridescence, material.iridescenceF0Metallic, singleScatteringMetallic, multiScatteringMetallic );
	#else
		computeMultiscattering( material.dfg, material.specularColor, material.specularF90, singleScatteringDielectric, multiScatteringDielectric );
		computeMultiscattering( material.dfg, material.diffuseColor, material.specularF90, singleScatteringMetallic, multiScatteringMetallic );
	#endif
	vec3 singleScattering = mix( singleScatteringDielectric, singleScatteringMetallic, material.metalness );
	vec3 multiScattering = mix( multiScatteringDielectric, multiScatteringMetallic, material.metalness );
	vec3 totalScatteringDielectric = singleScatteringDielectric + multiScatteringDielectric;
	#ifdef USE_DIFFUSE_ROUGHNESS
		float dotNV = saturate( dot( geometryNormal, geometryViewDir ) );
		vec3 diffuse = EON_DirectionalAlbedo( material.diffuseColor, material.diffuseRoughness, dotNV ) * ( 1.0 - material.metalness ) * ( 1.0 - totalScatteringDielectric );
	#else
		vec3 diffuse = material.diffuseContribution * ( 1.0 - totalScatteringDielectric );
	#endif
	vec3 cosineWeightedIrradiance = irradiance * RECIPROCAL_PI;
	vec3 indirectSpecular = radiance * singleScattering;
	indirectSpecular += multiScattering * cosineWeightedIrradiance;
	vec3 indirectDiffuse = diffuse * cosineWeightedIrradiance;
	#ifdef USE_SHEEN
		float sheenAlbedo = IBLSheenBRDF( geometryNormal, geometryViewDir, material.sheenRoughness );
		float sheenEnergyComp = 1.0 - max3( material.sheenColor ) * sheenAlbedo;
		indirectSpecular *= sheenEnergyComp;
		indirectDiffuse *= sheenEnergyComp;
	#endif
	reflectedLight.indirectSpecular += indirectSpecular;
	reflectedLight.indirectDiffuse += indirectDiffuse;
}
#define RE_Direct				RE_Direct_Physical
#define RE_Direct_RectArea		RE_Direct_RectArea_Physical
#define RE_IndirectDiffuse		RE_IndirectDiffuse_Physical
#define RE_IndirectSpecular		RE_IndirectSpecular_Physical
float computeSpecularOcclusion( const in float dotNV, const in float ambientOcclusion, const in float roughness ) {
	return saturate( pow( dotNV + ambientOcclusion, exp2( - 16.0 * roughness - 1.0 ) ) - 1.0 + ambientOcclusion );
}`,vR=`
vec3 geometryPosition = - vViewPosition;
vec3 geometryNormal = normal;
vec3 geometryViewDir = ( isOrthographic ) ? vec3( 0, 0, 1 ) : normalize( vViewPosition );
vec3 geometryClearcoatNormal = vec3( 0.0 );
#ifdef USE_CLEARCOAT
	geometryClearcoatNormal = clearcoatNormal;
#endif
#ifdef USE_IRIDESCENCE
	float dotNVi = saturate( dot( normal, geometryViewDir ) );
	if ( material.iridescenceThickness == 0.0 ) {
		material.iridescence = 0.0;
	} else {
		material.iridescence = saturate( material.iridescence );
	}
	if ( material.iridescence > 0.0 ) {
		vec3 iridescenceFresnelDielectric = evalIridescence( 1.0, material.iridescenceIOR, dotNVi, material.iridescenceThickness, material.specularColor );
		vec3 iridescenceFresnelMetallic = evalIridescence( 1.0, material.iridescenceIOR, dotNVi, material.iridescenceThickness, material.diffuseColor );
		material.iridescenceFresnel = mix( iridescenceFresnelDielectric, iridescenceFresnelMetallic, material.metalness );
		material.iridescenceF0Dielectric = Schlick_to_F0( iridescenceFresnelDielectric, 1.0, dotNVi );
		material.iridescenceF0Metallic = Schlick_to_F0( iridescenceFresnelMetallic, 1.0, dotNVi );
	}
#endif
#ifdef STANDARD
	float dotNVms = saturate( dot( geometryNormal, geometryViewDir ) );
	material.dfg = texture2D( dfgLUT, vec2( material.roughness, dotNVms ) ).rg;
	#if ( NUM_SUN_LIGHTS > 0 || NUM_DIR_LIGHTS > 0 || NUM_POINT_LIGHTS > 0 || NUM_SPOT_LIGHTS > 0 )
		float EssMs = material.dfg.x + material.dfg.y;
		material.multiScatteringCompensation = 1.0 + material.specularColorBlended * ( 1.0 / EssMs - 1.0 );
	#endif
#endif
IncidentLight directLight;
#if ( NUM_POINT_LIGHTS > 0 ) && defined( RE_Direct )
	PointLight pointLight;
	#if defined( USE_SHADOWMAP ) && NUM_POINT_LIGHT_SHADOWS > 0
	PointLightShadow pointLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_POINT_LIGHTS; i ++ ) {
		pointLight = pointLights[ i ];
		getPointLightInfo( pointLight, geometryPosition, directLight );
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_POINT_LIGHT_SHADOWS ) && ( defined( SHADOWMAP_TYPE_PCF ) || defined( SHADOWMAP_TYPE_BASIC ) )
		pointLightShadow = pointLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getPointShadow( pointShadowMap[ i ], pointLightShadow.shadowMapSize, pointLightShadow.shadowIntensity, pointLightShadow.shadowBias, pointLightShadow.shadowRadius, vPointShadowCoord[ i ], pointLightShadow.shadowCameraNear, pointLightShadow.shadowCameraFar ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_SPOT_LIGHTS > 0 ) && defined( RE_Direct )
	SpotLight spotLight;
	vec4 spotColor;
	vec3 spotLightCoord;
	bool inSpotLightMap;
	#if defined( USE_SHADOWMAP ) && NUM_SPOT_LIGHT_SHADOWS > 0
	SpotLightShadow spotLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SPOT_LIGHTS; i ++ ) {
		spotLight = spotLights[ i ];
		getSpotLightInfo( spotLight, geometryPosition, directLight );
		#if ( UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS_WITH_MAPS )
		#define SPOT_LIGHT_MAP_INDEX UNROLLED_LOOP_INDEX
		#elif ( UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS )
		#define SPOT_LIGHT_MAP_INDEX NUM_SPOT_LIGHT_MAPS
		#else
		#define SPOT_LIGHT_MAP_INDEX ( UNROLLED_LOOP_INDEX - NUM_SPOT_LIGHT_SHADOWS + NUM_SPOT_LIGHT_SHADOWS_WITH_MAPS )
		#endif
		#if ( SPOT_LIGHT_MAP_INDEX < NUM_SPOT_LIGHT_MAPS )
			spotLightCoord = vSpotLightCoord[ i ].xyz / vSpotLightCoord[ i ].w;
			inSpotLightMap = all( lessThan( abs( spotLightCoord * 2. - 1. ), vec3( 1.0 ) ) );
			spotColor = texture2D( spotLightMap[ SPOT_LIGHT_MAP_INDEX ], spotLightCoord.xy );
			directLight.color = inSpotLightMap ? directLight.color * spotColor.rgb : directLight.color;
		#endif
		#undef SPOT_LIGHT_MAP_INDEX
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS )
		spotLightShadow = spotLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getShadow( spotShadowMap[ i ], spotLightShadow.shadowMapSize, spotLightShadow.shadowIntensity, spotLightShadow.shadowBias, spotLightShadow.shadowRadius, vSpotLightCoord[ i ] ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_SUN_LIGHTS > 0 ) && defined( RE_Direct )
	SunLight sunLight;
	#if defined( USE_SHADOWMAP ) && NUM_SUN_LIGHT_SHADOWS > 0
	SunLightShadow sunLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SUN_LIGHTS; i ++ ) {
		sunLight = sunLights[ i ];
		getSunLightInfo( sunLight, directLight );
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_SUN_LIGHT_SHADOWS )
		sunLightShadow = sunLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getSunShadow( sunShadowMap[ i ], sunLightShadow, UNROLLED_LOOP_INDEX ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_DIR_LIGHTS > 0 ) && defined( RE_Direct )
	DirectionalLight directionalLight;
	#if defined( USE_SHADOWMAP ) && NUM_DIR_LIGHT_SHADOWS > 0
	DirectionalLightShadow directionalLightShadow;
	#endif
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_DIR_LIGHTS; i ++ ) {
		directionalLight = directionalLights[ i ];
		getDirectionalLightInfo( directionalLight, directLight );
		#if defined( USE_SHADOWMAP ) && ( UNROLLED_LOOP_INDEX < NUM_DIR_LIGHT_SHADOWS )
		directionalLightShadow = directionalLightShadows[ i ];
		directLight.color *= ( directLight.visible && receiveShadow ) ? getShadow( directionalShadowMap[ i ], directionalLightShadow.shadowMapSize, directionalLightShadow.shadowIntensity, directionalLightShadow.shadowBias, directionalLightShadow.shadowRadius, vDirectionalShadowCoord[ i ] ) : 1.0;
		#endif
		RE_Direct( directLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if ( NUM_RECT_AREA_LIGHTS > 0 ) && defined( RE_Direct_RectArea )
	RectAreaLight rectAreaLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_RECT_AREA_LIGHTS; i ++ ) {
		rectAreaLight = rectAreaLights[ i ];
		RE_Direct_RectArea( rectAreaLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
	}
	#pragma unroll_loop_end
#endif
#if defined( RE_IndirectDiffuse )
	vec3 iblIrradiance = vec3( 0.0 );
	vec3 irradiance = getAmbientLightIrradiance( ambientLightColor );
	#if defined( USE_LIGHT_PROBES )
		irradiance += getLightProbeIrradiance( lightProbe, geometryNormal );
	#endif
	#if ( NUM_HEMI_LIGHTS > 0 )
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_HEMI_LIGHTS; i ++ ) {
			irradiance += getHemisphereLightIrradiance( hemisphereLights[ i ], geometryNormal );
		}
		#pragma unroll_loop_end
	#endif
	#if NUM_LIGHT_PROBE_GRIDS > 0
		vec3 probeWorldPos = ( ( vec4( geometryPosition, 1.0 ) - viewMatrix[ 3 ] ) * viewMatrix ).xyz;
		vec3 probeWorldNormal = transformNormalByInverseViewMatrix( geometryNormal, viewMatrix );
		int probeGrid = - 1;
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_LIGHT_PROBE_GRIDS; i ++ ) {
			if ( isInsideLightProbeGrid( probeWorldPos, probeWorldNormal, probesMin[ i ], probesMax[ i ], probesResolution[ i ] ) ) probeGrid = UNROLLED_LOOP_INDEX;
		}
		#pragma unroll_loop_end
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_LIGHT_PROBE_GRIDS; i ++ ) {
			if ( probeGrid == UNROLLED_LOOP_INDEX ) irradiance += getLightProbeGridIrradiance( probesSH[ i ], probesMin[ i ], probesMax[ i ], probesResolution[ i ], probeWorldPos, probeWorldNormal );
		}
		#pragma unroll_loop_end
	#endif
#endif
#if defined( RE_IndirectSpecular )
	vec3 radiance = vec3( 0.0 );
	vec3 clearcoatRadiance = vec3( 0.0 );
#endif`,bR=`#if defined( RE_IndirectDiffuse )
	#ifdef USE_LIGHTMAP
		vec4 lightMapTexel = texture2D( lightMap, vLightMapUv );
		vec3 lightMapIrradiance = lightMapTexel.rgb * lightMapIntensity;
		irradiance += lightMapIrradiance;
	#endif
	#if defined( USE_ENVMAP ) && defined( ENVMAP_TYPE_PMREM )
		#if defined( STANDARD ) || defined( LAMBERT ) || defined( PHONG )
			iblIrradiance += getIBLIrradiance( geometryNormal );
		#endif
	#endif
#endif
#if defined( USE_ENVMAP ) && defined( RE_IndirectSpecular )
	#ifdef USE_ANISOTROPY
		vec3 iblRadiance = getIBLAnisotropyRadiance( geometryViewDir, geometryNormal, material.roughness, material.anisotropyB, material.anisotropy );
	#else
		vec3 iblRadiance = getIBLRadiance( geometryViewDir, geometryNormal, material.roughness );
	#endif
	#ifdef USE_RETROREFLECTION
		#ifdef USE_ANISOTROPY
			vec3 retroIBLRadiance = getIBLAnisotropyRetroRadiance( geometryViewDir, geometryNormal, material.roughness, material.anisotropyB, material.anisotropy );
		#else
			vec3 retroIBLRadiance = getIBLRetroRadiance( geometryViewDir, geometryNormal, material.roughness );
		#endif
		iblRadiance = mix( iblRadiance, retroIBLRadiance, saturate( material.retroreflectivity ) );
	#endif
	radiance += iblRadiance;
	#ifdef USE_CLEARCOAT
		clearcoatRadiance += getIBLRadiance( geometryViewDir, geometryClearcoatNormal, material.clearcoatRoughness );
	#endif
#endif`,SR=`#if defined( RE_IndirectDiffuse )
	#if defined( LAMBERT ) || defined( PHONG )
		irradiance += iblIrradiance;
	#endif
	RE_IndirectDiffuse( irradiance, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
#endif
#if defined( RE_IndirectSpecular )
	RE_IndirectSpecular( radiance, iblIrradiance, clearcoatRadiance, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );
#endif`,MR=`#if NUM_LIGHT_PROBE_GRIDS > 0
uniform highp sampler3D probesSH[ NUM_LIGHT_PROBE_GRIDS ];
uniform vec3 probesMin[ NUM_LIGHT_PROBE_GRIDS ];
uniform vec3 probesMax[ NUM_LIGHT_PROBE_GRIDS ];
uniform vec3 probesResolution[ NUM_LIGHT_PROBE_GRIDS ];
bool isInsideLightProbeGrid( vec3 worldPos, vec3 worldNormal, vec3 probesMin, vec3 probesMax, vec3 probesResolution ) {
	vec3 spacing = ( probesMax - probesMin ) / probesResolution;
	vec3 samplePos = worldPos + worldNormal * spacing * 0.5;
	vec3 margin = spacing * 0.01;
	return all( greaterThanEqual( samplePos, probesMin - margin ) ) && all( lessThanEqual( samplePos, probesMax + margin ) );
}
vec3 getLightProbeGridIrradiance( highp sampler3D probesSH, vec3 probesMin, vec3 probesMax, vec3 probesResolution, vec3 worldPos, vec3 worldNormal ) {
	vec3 res = probesResolution;
	vec3 gridRange = probesMax - probesMin;
	vec3 probeSpacing = gridRange / res;
	vec3 samplePos = worldPos + worldNormal * probeSpacing * 0.5;
	vec3 uvw = clamp( ( samplePos - probesMin ) / gridRange, 0.5 / res, 1.0 - 0.5 / res );
	float nz          = res.z;
	float paddedSlices = nz + 2.0;
	float atlasDepth  = 7.0 * paddedSlices;
	float uvZBase     = uvw.z * nz + 1.0;
	vec4 s0 = texture( probesSH, vec3( uvw.xy, ( uvZBase                       ) / atlasDepth ) );
	vec4 s1 = texture( probesSH, vec3( uvw.xy, ( uvZBase +       paddedSlices   ) / atlasDepth ) );
	vec4 s2 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 2.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s3 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 3.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s4 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 4.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s5 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 5.0 * paddedSlices   ) / atlasDepth ) );
	vec4 s6 = texture( probesSH, vec3( uvw.xy, ( uvZBase + 6.0 * paddedSlices   ) / atlasDepth ) );
	vec3 c0 = s0.xyz;
	vec3 c1 = vec3( s0.w, s1.xy );
	vec3 c2 = vec3( s1.zw, s2.x );
	vec3 c3 = s2.yzw;
	vec3 c4 = s3.xyz;
	vec3 c5 = vec3( s3.w, s4.xy );
	vec3 c6 = vec3( s4.zw, s5.x );
	vec3 c7 = s5.yzw;
	vec3 c8 = s6.xyz;
	float x = worldNormal.x, y = worldNormal.y, z = worldNormal.z;
	vec3 result = c0 * 0.886227;
	result += c1 * 2.0 * 0.511664 * y;
	result += c2 * 2.0 * 0.511664 * z;
	result += c3 * 2.0 * 0.511664 * x;
	result += c4 * 2.0 * 0.429043 * x * y;
	result += c5 * 2.0 * 0.429043 * y * z;
	result += c6 * ( 0.743125 * z * z - 0.247708 );
	result += c7 * 2.0 * 0.429043 * x * z;
	result += c8 * 0.429043 * ( x * x - y * y );
	return max( result, vec3( 0.0 ) );
}
#endif`,ER=`#if defined( USE_LOGARITHMIC_DEPTH_BUFFER )
	gl_FragDepth = vIsPerspective == 0.0 ? gl_FragCoord.z : log2( vFragDepth ) * logDepthBufFC * 0.5;
#endif`,wR=`#if defined( USE_LOGARITHMIC_DEPTH_BUFFER )
	uniform float logDepthBufFC;
	varying float vFragDepth;
	varying float vIsPerspective;
#endif`,AR=`#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
	varying float vFragDepth;
	varying float vIsPerspective;
#endif`,TR=`#ifdef USE_LOGARITHMIC_DEPTH_BUFFER
	vFragDepth = 1.0 + gl_Position.w;
	vIsPerspective = float( isPerspectiveMatrix( projectionMatrix ) );
#endif`,RR=`#ifdef USE_MAP
	vec4 sampledDiffuseColor = texture2D( map, vMapUv );
	#ifdef DECODE_VIDEO_TEXTURE
		sampledDiffuseColor = sRGBTransferEOTF( sampledDiffuseColor );
	#endif
	diffuseColor *= sampledDiffuseColor;
#endif`,IR=`#ifdef USE_MAP
	uniform sampler2D map;
#endif`,CR=`#if defined( USE_MAP ) || defined( USE_ALPHAMAP )
	#if defined( USE_POINTS_UV )
		vec2 uv = vUv;
	#else
		vec2 uv = ( uvTransform * vec3( gl_PointCoord.x, 1.0 - gl_PointCoord.y, 1 ) ).xy;
	#endif
#endif
#ifdef USE_MAP
	diffuseColor *= texture2D( map, uv );
#endif
#ifdef USE_ALPHAMAP
	diffuseColor.a *= texture2D( alphaMap, uv ).g;
#endif`,NR=`#if defined( USE_POINTS_UV )
	varying vec2 vUv;
#else
	#if defined( USE_MAP ) || defined( USE_ALPHAMAP )
		uniform mat3 uvTransform;
	#endif
#endif
#ifdef USE_MAP
	uniform sampler2D map;
#endif
#ifdef USE_ALPHAMAP
	uniform sampler2D alphaMap;
#endif`,PR=`float metalnessFactor = metalness;
#ifdef USE_METALNESSMAP
	vec4 texelMetalness = texture2D( metalnessMap, vMetalnessMapUv );
	metalnessFactor *= texelMetalness.b;
#endif`,LR=`#ifdef USE_METALNESSMAP
	uniform sampler2D metalnessMap;
#endif`,DR=`#ifdef USE_INSTANCING_MORPH
	float morphTargetInfluences[ MORPHTARGETS_COUNT ];
	float morphTargetBaseInfluence = texelFetch( morphTexture, ivec2( 0, gl_InstanceID ), 0 ).r;
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		morphTargetInfluences[i] =  texelFetch( morphTexture, ivec2( i + 1, gl_InstanceID ), 0 ).r;
	}
#endif`,UR=`#if defined( USE_MORPHCOLORS )
	#if defined( USE_COLOR_ALPHA )
		vColor *= morphTargetBaseInfluence;
	#elif defined( USE_COLOR )
		vColor.rgb *= morphTargetBaseInfluence;
	#endif
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		#if defined( USE_COLOR_ALPHA )
			if ( morphTargetInfluences[ i ] != 0.0 ) vColor += getMorph( gl_VertexID, i, 2 ) * morphTargetInfluences[ i ];
		#elif defined( USE_COLOR )
			if ( morphTargetInfluences[ i ] != 0.0 ) vColor.rgb += getMorph( gl_VertexID, i, 2 ).rgb * morphTargetInfluences[ i ];
		#endif
	}
#endif`,OR=`#ifdef USE_MORPHNORMALS
	objectNormal *= morphTargetBaseInfluence;
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		if ( morphTargetInfluences[ i ] != 0.0 ) objectNormal += getMorph( gl_VertexID, i, 1 ).xyz * morphTargetInfluences[ i ];
	}
#endif`,FR=`#ifdef USE_MORPHTARGETS
	#ifndef USE_INSTANCING_MORPH
		uniform float morphTargetBaseInfluence;
		uniform float morphTargetInfluences[ MORPHTARGETS_COUNT ];
	#endif
	uniform sampler2DArray morphTargetsTexture;
	uniform ivec2 morphTargetsTextureSize;
	vec4 getMorph( const in int vertexIndex, const in int morphTargetIndex, const in int offset ) {
		int texelIndex = vertexIndex * MORPHTARGETS_TEXTURE_STRIDE + offset;
		int y = texelIndex / morphTargetsTextureSize.x;
		int x = texelIndex - y * morphTargetsTextureSize.x;
		ivec3 morphUV = ivec3( x, y, morphTargetIndex );
		return texelFetch( morphTargetsTexture, morphUV, 0 );
	}
#endif`,BR=`#ifdef USE_MORPHTARGETS
	transformed *= morphTargetBaseInfluence;
	for ( int i = 0; i < MORPHTARGETS_COUNT; i ++ ) {
		if ( morphTargetInfluences[ i ] != 0.0 ) transformed += getMorph( gl_VertexID, i, 0 ).xyz * morphTargetInfluences[ i ];
	}
#endif`,kR=`float faceDirection = gl_FrontFacing ? 1.0 : - 1.0;
#ifdef FLAT_SHADED
	vec3 fdx = dFdx( vViewPosition );
	vec3 fdy = dFdy( vViewPosition );
	vec3 normal = normalize( cross( fdx, fdy ) );
#else
	vec3 normal = normalize( vNormal );
	#ifdef DOUBLE_SIDED
		normal *= faceDirection;
	#endif
#endif
#if defined( USE_NORMALMAP_TANGENTSPACE ) || defined( USE_CLEARCOAT_NORMALMAP ) || defined( USE_ANISOTROPY )
	#ifdef USE_TANGENT
		mat3 tbn = mat3( normalize( vTangent ), normalize( vBitangent ), normal );
	#else
		mat3 tbn = getTangentFrame( - vViewPosition, normal,
		#if defined( USE_NORMALMAP )
			vNormalMapUv
		#elif defined( USE_CLEARCOAT_NORMALMAP )
			vClearcoatNormalMapUv
		#else
			vUv
		#endif
		);
	#endif
	#ifdef DOUBLE_SIDED
		tbn[0] *= faceDirection;
		tbn[1] *= faceDirection;
	#endif
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	#ifdef USE_TANGENT
		mat3 tbn2 = mat3( normalize( vTangent ), normalize( vBitangent ), normal );
	#else
		mat3 tbn2 = getTangentFrame( - vViewPosition, normal, vClearcoatNormalMapUv );
	#endif
	#ifdef DOUBLE_SIDED
		tbn2[0] *= faceDirection;
		tbn2[1] *= faceDirection;
	#endif
#endif
vec3 nonPerturbedNormal = normal;`,VR=`#ifdef USE_NORMALMAP_OBJECTSPACE
	normal = texture2D( normalMap, vNormalMapUv ).xyz * 2.0 - 1.0;
	#ifdef FLIP_SIDED
		normal = - normal;
	#endif
	#ifdef DOUBLE_SIDED
		normal = normal * faceDirection;
	#endif
	normal = normalize( normalMatrix * normal );
#elif defined( USE_NORMALMAP_TANGENTSPACE )
	vec3 mapN = texture2D( normalMap, vNormalMapUv ).xyz * 2.0 - 1.0;
	#if defined( USE_PACKED_NORMALMAP )
		mapN = vec3( mapN.xy, sqrt( saturate( 1.0 - dot( mapN.xy, mapN.xy ) ) ) );
	#endif
	mapN.xy *= normalScale;
	normal = normalize( tbn * mapN );
#elif defined( USE_BUMPMAP )
	normal = perturbNormalArb( - vViewPosition, normal, dHdxy_fwd(), faceDirection );
#endif`,GR=`#ifndef FLAT_SHADED
	varying vec3 vNormal;
	#ifdef USE_TANGENT
		varying vec3 vTangent;
		varying vec3 vBitangent;
	#endif
#endif`,zR=`#ifndef FLAT_SHADED
	varying vec3 vNormal;
	#ifdef USE_TANGENT
		varying vec3 vTangent;
		varying vec3 vBitangent;
	#endif
#endif`,HR=`#ifndef FLAT_SHADED
	vNormal = normalize( transformedNormal );
	#ifdef USE_TANGENT
		vTangent = normalize( transformedTangent );
		vBitangent = normalize( cross( vNormal, vTangent ) * tangent.w );
		#ifdef FLIP_SIDED
			vBitangent = - vBitangent;
		#endif
	#endif
#endif`,WR=`#ifdef USE_NORMALMAP
	uniform sampler2D normalMap;
	uniform vec2 normalScale;
#endif
#ifdef USE_NORMALMAP_OBJECTSPACE
	uniform mat3 normalMatrix;
#endif
#if ! defined ( USE_TANGENT ) && ( defined ( USE_NORMALMAP_TANGENTSPACE ) || defined ( USE_CLEARCOAT_NORMALMAP ) || defined( USE_ANISOTROPY ) )
	mat3 getTangentFrame( vec3 eye_pos, vec3 surf_norm, vec2 uv ) {
		vec3 q0 = dFdx( eye_pos.xyz );
		vec3 q1 = dFdy( eye_pos.xyz );
		vec2 st0 = dFdx( uv.st );
		vec2 st1 = dFdy( uv.st );
		vec3 N = surf_norm;
		vec3 q1perp = cross( q1, N );
		vec3 q0perp = cross( N, q0 );
		vec3 T = q1perp * st0.x + q0perp * st1.x;
		vec3 B = q1perp * st0.y + q0perp * st1.y;
		float det = max( dot( T, T ), dot( B, B ) );
		float scale = ( det == 0.0 ) ? 0.0 : inversesqrt( det );
		return mat3( T * scale, B * scale, N );
	}
#endif`,XR=`#ifdef USE_CLEARCOAT
	vec3 clearcoatNormal = nonPerturbedNormal;
#endif`,YR=`#ifdef USE_CLEARCOAT_NORMALMAP
	vec3 clearcoatMapN = texture2D( clearcoatNormalMap, vClearcoatNormalMapUv ).xyz * 2.0 - 1.0;
	clearcoatMapN.xy *= clearcoatNormalScale;
	clearcoatNormal = normalize( tbn2 * clearcoatMapN );
#endif`,ZR=`#ifdef USE_CLEARCOATMAP
	uniform sampler2D clearcoatMap;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	uniform sampler2D clearcoatNormalMap;
	uniform vec2 clearcoatNormalScale;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	uniform sampler2D clearcoatRoughnessMap;
#endif`,KR=`#ifdef USE_IRIDESCENCEMAP
	uniform sampler2D iridescenceMap;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	uniform sampler2D iridescenceThicknessMap;
#endif`,$R=`#ifdef OPAQUE
diffuseColor.a = 1.0;
#endif
#ifdef USE_TRANSMISSION
diffuseColor.a *= material.transmissionAlpha;
#endif
gl_FragColor = vec4( outgoingLight, diffuseColor.a );`,qR=`vec3 packNormalToRGB( const in vec3 normal ) {
	return normalize( normal ) * 0.5 + 0.5;
}
vec3 unpackRGBToNormal( const in vec3 rgb ) {
	return 2.0 * rgb.xyz - 1.0;
}
const float PackUpscale = 256. / 255.;const float UnpackDownscale = 255. / 256.;const float ShiftRight8 = 1. / 256.;
const float Inv255 = 1. / 255.;
const vec4 PackFactors = vec4( 1.0, 256.0, 256.0 * 256.0, 256.0 * 256.0 * 256.0 );
const vec2 UnpackFactors2 = vec2( UnpackDownscale, 1.0 / PackFactors.g );
const vec3 UnpackFactors3 = vec3( UnpackDownscale / PackFactors.rg, 1.0 / PackFactors.b );
const vec4 UnpackFactors4 = vec4( UnpackDownscale / PackFactors.rgb, 1.0 / PackFactors.a );
vec4 packDepthToRGBA( const in float v ) {
	if( v <= 0.0 )
		return vec4( 0., 0., 0., 0. );
	if( v >= 1.0 )
		return vec4( 1., 1., 1., 1. );
	float vuf;
	float af = modf( v * PackFactors.a, vuf );
	float bf = modf( vuf * ShiftRight8, vuf );
	float gf = modf( vuf * ShiftRight8, vuf );
	return vec4( vuf * Inv255, gf * PackUpscale, bf * PackUpscale, af );
}
vec3 packDepthToRGB( const in float v ) {
	if( v <= 0.0 )
		return vec3( 0., 0., 0. );
	if( v >= 1.0 )
		return vec3( 1., 1., 1. );
	float vuf;
	float bf = modf( v * PackFactors.b, vuf );
	float gf = modf( vuf * ShiftRight8, vuf );
	return vec3( vuf * Inv255, gf * PackUpscale, bf );
}
vec2 packDepthToRG( const in float v ) {
	if( v <= 0.0 )
		return vec2( 0., 0. );
	if( v >= 1.0 )
		return vec2( 1., 1. );
	float vuf;
	float gf = modf( v * 256., vuf );
	return vec2( vuf * Inv255, gf );
}
float unpackRGBAToDepth( const in vec4 v ) {
	return dot( v, UnpackFactors4 );
}
float unpackRGBToDepth( const in vec3 v ) {
	return dot( v, UnpackFactors3 );
}
float unpackRGToDepth( const in vec2 v ) {
	return v.r * UnpackFactors2.r + v.g * UnpackFactors2.g;
}
vec4 pack2HalfToRGBA( const in vec2 v ) {
	vec4 r = vec4( v.x, fract( v.x * 255.0 ), v.y, fract( v.y * 255.0 ) );
	return vec4( r.x - r.y / 255.0, r.y, r.z - r.w / 255.0, r.w );
}
vec2 unpackRGBATo2Half( const in vec4 v ) {
	return vec2( v.x + ( v.y / 255.0 ), v.z + ( v.w / 255.0 ) );
}
float viewZToOrthographicDepth( const in float viewZ, const in float near, const in float far ) {
	return ( viewZ + near ) / ( near - far );
}
float orthographicDepthToViewZ( const in float depth, const in float near, const in float far ) {
	#ifdef USE_REVERSED_DEPTH_BUFFER
	
		return depth * ( far - near ) - far;
	#else
		return depth * ( near - far ) - near;
	#endif
}
float viewZToPerspectiveDepth( const in float viewZ, const in float near, const in float far ) {
	return ( ( near + viewZ ) * far ) / ( ( far - near ) * viewZ );
}
float perspectiveDepthToViewZ( const in float depth, const in float near, const in float far ) {
	
	#ifdef USE_REVERSED_DEPTH_BUFFER
		return ( near * far ) / ( ( near - far ) * depth - near );
	#else
		return ( near * far ) / ( ( far - near ) * depth - far );
	#endif
}`,JR=`#ifdef PREMULTIPLIED_ALPHA
	gl_FragColor.rgb *= gl_FragColor.a;
#endif`,jR=`vec4 mvPosition = vec4( transformed, 1.0 );
#ifdef USE_BATCHING
	mvPosition = batchingMatrix * mvPosition;
#endif
#ifdef USE_INSTANCING
	mvPosition = instanceMatrix * mvPosition;
#endif
mvPosition = modelViewMatrix * mvPosition;
gl_Position = projectionMatrix * mvPosition;`,QR=`#ifdef DITHERING
	gl_FragColor.rgb = dithering( gl_FragColor.rgb );
#endif`,eI=`#ifdef DITHERING
	vec3 dithering( vec3 color ) {
		float grid_position = rand( gl_FragCoord.xy );
		vec3 dither_shift_RGB = vec3( 0.25 / 255.0, -0.25 / 255.0, 0.25 / 255.0 );
		dither_shift_RGB = mix( 2.0 * dither_shift_RGB, -2.0 * dither_shift_RGB, grid_position );
		return color + dither_shift_RGB;
	}
#endif`,tI=`float roughnessFactor = roughness;
#ifdef USE_ROUGHNESSMAP
	vec4 texelRoughness = texture2D( roughnessMap, vRoughnessMapUv );
	roughnessFactor *= texelRoughness.g;
#endif`,nI=`#ifdef USE_ROUGHNESSMAP
	uniform sampler2D roughnessMap;
#endif`,iI=`#if NUM_SPOT_LIGHT_COORDS > 0
	varying vec4 vSpotLightCoord[ NUM_SPOT_LIGHT_COORDS ];
#endif
#if NUM_SPOT_LIGHT_MAPS > 0
	uniform sampler2D spotLightMap[ NUM_SPOT_LIGHT_MAPS ];
#endif
#ifdef USE_SHADOWMAP
	#if NUM_SUN_LIGHT_SHADOWS > 0
		#define SUN_LIGHT_CASCADES 2
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform sampler2DShadow sunShadowMap[ NUM_SUN_LIGHT_SHADOWS ];
		#else
			uniform sampler2D sunShadowMap[ NUM_SUN_LIGHT_SHADOWS ];
		#endif
		uniform mat4 sunShadowMatrix[ NUM_SUN_LIGHT_SHADOWS * SUN_LIGHT_CASCADES ];
		uniform vec4 sunShadowCascade[ NUM_SUN_LIGHT_SHADOWS * SUN_LIGHT_CASCADES ];
		varying vec4 vSunShadowWorldPosition;
		varying vec3 vSunShadowWorldNormal;
		struct SunLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform SunLightShadow sunLightShadows[ NUM_SUN_LIGHT_SHADOWS ];
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform sampler2DShadow directionalShadowMap[ NUM_DIR_LIGHT_SHADOWS ];
		#else
			uniform sampler2D directionalShadowMap[ NUM_DIR_LIGHT_SHADOWS ];
		#endif
		varying vec4 vDirectionalShadowCoord[ NUM_DIR_LIGHT_SHADOWS ];
		struct DirectionalLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform DirectionalLightShadow directionalLightShadows[ NUM_DIR_LIGHT_SHADOWS ];
	#endif
	#if NUM_SPOT_LIGHT_SHADOWS > 0
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform sampler2DShadow spotShadowMap[ NUM_SPOT_LIGHT_SHADOWS ];
		#else
			uniform sampler2D spotShadowMap[ NUM_SPOT_LIGHT_SHADOWS ];
		#endif
		struct SpotLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform SpotLightShadow spotLightShadows[ NUM_SPOT_LIGHT_SHADOWS ];
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
		#if defined( SHADOWMAP_TYPE_PCF )
			uniform samplerCubeShadow pointShadowMap[ NUM_POINT_LIGHT_SHADOWS ];
		#elif defined( SHADOWMAP_TYPE_BASIC )
			uniform samplerCube pointShadowMap[ NUM_POINT_LIGHT_SHADOWS ];
		#endif
		varying vec4 vPointShadowCoord[ NUM_POINT_LIGHT_SHADOWS ];
		struct PointLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
			float shadowCameraNear;
			float shadowCameraFar;
		};
		uniform PointLightShadow pointLightShadows[ NUM_POINT_LIGHT_SHADOWS ];
	#endif
	#if defined( SHADOWMAP_TYPE_PCF )
		float interleavedGradientNoise( vec2 position ) {
			return fract( 52.9829189 * fract( dot( position, vec2( 0.06711056, 0.00583715 ) ) ) );
		}
		vec2 vogelDiskSample( int sampleIndex, int samplesCount, float phi ) {
			const float goldenAngle = 2.399963229728653;
			float r = sqrt( ( float( sampleIndex ) + 0.5 ) / float( samplesCount ) );
			float theta = float( sampleIndex ) * goldenAngle + phi;
			return vec2( cos( theta ), sin( theta ) ) * r;
		}
	#endif
	#if defined( SHADOWMAP_TYPE_PCF )
		float getShadow( sampler2DShadow shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord ) {
			float shadow = 1.0;
			shadowCoord.xyz /= shadowCoord.w;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				shadowCoord.z -= shadowBias;
			#else
				shadowCoord.z += shadowBias;
			#endif
			bool inFrustum = shadowCoord.x >= 0.0 && shadowCoord.x <= 1.0 && shadowCoord.y >= 0.0 && shadowCoord.y <= 1.0;
			bool frustumTest = inFrustum && shadowCoord.z <= 1.0;
			if ( frustumTest ) {
				vec2 texelSize = vec2( 1.0 ) / shadowMapSize;
				vec2 radius = shadowRadius * texelSize;
				float phi = interleavedGradientNoise( gl_FragCoord.xy ) * PI2;
				shadow = (
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 0, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 1, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 2, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 3, 5, phi ) * radius, shadowCoord.z ) ) +
					texture( shadowMap, vec3( shadowCoord.xy + vogelDiskSample( 4, 5, phi ) * radius, shadowCoord.z ) )
				) * 0.2;
			}
			return mix( 1.0, shadow, shadowIntensity );
		}
	#elif defined( SHADOWMAP_TYPE_VSM )
		float getShadow( sampler2D shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord ) {
			float shadow = 1.0;
			shadowCoord.xyz /= shadowCoord.w;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				shadowCoord.z -= shadowBias;
			#else
				shadowCoord.z += shadowBias;
			#endif
			bool inFrustum = shadowCoord.x >= 0.0 && shadowCoord.x <= 1.0 && shadowCoord.y >= 0.0 && shadowCoord.y <= 1.0;
			bool frustumTest = inFrustum && shadowCoord.z <= 1.0;
			if ( frustumTest ) {
				vec2 distribution = texture2D( shadowMap, shadowCoord.xy ).rg;
				float mean = distribution.x;
				float variance = distribution.y * distribution.y;
				#ifdef USE_REVERSED_DEPTH_BUFFER
					float hard_shadow = step( mean, shadowCoord.z );
				#else
					float hard_shadow = step( shadowCoord.z, mean );
				#endif
				
				if ( hard_shadow == 1.0 ) {
					shadow = 1.0;
				} else {
					variance = max( variance, 0.0000001 );
					float d = shadowCoord.z - mean;
					float p_max = variance / ( variance + d * d );
					p_max = clamp( ( p_max - 0.3 ) / 0.65, 0.0, 1.0 );
					shadow = max( hard_shadow, p_max );
				}
			}
			return mix( 1.0, shadow, shadowIntensity );
		}
	#else
		float getShadow( sampler2D shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord ) {
			float shadow = 1.0;
			shadowCoord.xyz /= shadowCoord.w;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				shadowCoord.z -= shadowBias;
			#else
				shadowCoord.z += shadowBias;
			#endif
			bool inFrustum = shadowCoord.x >= 0.0 && shadowCoord.x <= 1.0 && shadowCoord.y >= 0.0 && shadowCoord.y <= 1.0;
			bool frustumTest = inFrustum && shadowCoord.z <= 1.0;
			if ( frustumTest ) {
				float depth = texture2D( shadowMap, shadowCoord.xy ).r;
				#ifdef USE_REVERSED_DEPTH_BUFFER
					shadow = step( depth, shadowCoord.z );
				#else
					shadow = step( shadowCoord.z, depth );
				#endif
			}
			return mix( 1.0, shadow, shadowIntensity );
		}
	#endif
	#if NUM_SUN_LIGHT_SHADOWS > 0
		float getSunShadow(
			#if defined( SHADOWMAP_TYPE_PCF )
				sampler2DShadow shadowMap,
			#else
				sampler2D shadowMap,
			#endif
			SunLightShadow sunLightShadow,
			int shadowIndex
		) {
			vec4 shadowWorldPosition = vec4( vSunShadowWorldPosition.xyz + vSunShadowWorldNormal * sunLightShadow.shadowNormalBias, 1.0 );
			float viewDepth = vSunShadowWorldPosition.w;
			int cascadeOffset = shadowIndex * SUN_LIGHT_CASCADES;
			float shadow = 1.0;
			for ( int i = SUN_LIGHT_CASCADES - 1; i >= 0; i -- ) {
				vec4 cascade = sunShadowCascade[ cascadeOffset + i ];
				if ( viewDepth >= cascade.x && viewDepth < cascade.y ) {
					float cascadeShadow = getShadow(
						shadowMap,
						sunLightShadow.shadowMapSize,
						sunLightShadow.shadowIntensity,
						sunLightShadow.shadowBias,
						sunLightShadow.shadowRadius,
						sunShadowMatrix[ cascadeOffset + i ] * shadowWorldPosition
					);
					shadow = mix( cascadeShadow, shadow, smoothstep( cascade.z, cascade.y, viewDepth ) );
				}
			}
			return shadow;
		}
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
	#if defined( SHADOWMAP_TYPE_PCF )
	float getPointShadow( samplerCubeShadow shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord, float shadowCameraNear, float shadowCameraFar ) {
		float shadow = 1.0;
		vec3 lightToPosition = shadowCoord.xyz;
		vec3 bd3D = normalize( lightToPosition );
		vec3 absVec = abs( lightToPosition );
		float viewSpaceZ = max( max( absVec.x, absVec.y ), absVec.z );
		if ( viewSpaceZ - shadowCameraFar <= 0.0 && viewSpaceZ - shadowCameraNear >= 0.0 ) {
			float lightDistance = length( lightToPosition );
			float depthRange = shadowCameraFar - shadowCameraNear;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				float depthA = - shadowCameraNear / depthRange - shadowBias;
				float depthB = shadowCameraNear * shadowCameraFar / ( depthRange * lightDistance );
			#else
				float depthA = shadowCameraFar / depthRange + shadowBias;
				float depthB = - shadowCameraNear * shadowCameraFar / ( depthRange * lightDistance );
			#endif
			float texelSize = shadowRadius / shadowMapSize.x;
			vec3 absDir = abs( bd3D );
			vec3 tangent = absDir.x > absDir.z ? vec3( 0.0, 1.0, 0.0 ) : vec3( 1.0, 0.0, 0.0 );
			tangent = normalize( cross( bd3D, tangent ) );
			vec3 bitangent = cross( bd3D, tangent );
			float phi = interleavedGradientNoise( gl_FragCoord.xy ) * PI2;
			shadow = 0.0;
			for ( int i = 0; i < 5; i ++ ) {
				vec2 offset = vogelDiskSample( i, 5, phi );
				vec3 direction = bd3D + ( tangent * offset.x + bitangent * offset.y ) * texelSize;
				vec3 absDirection = abs( direction );
				float dp = depthA + depthB / max( max( absDirection.x, absDirection.y ), absDirection.z );
				shadow += texture( shadowMap, vec4( direction, dp ) );
			}
			shadow *= 0.2;
		}
		return mix( 1.0, shadow, shadowIntensity );
	}
	#elif defined( SHADOWMAP_TYPE_BASIC )
	float getPointShadow( samplerCube shadowMap, vec2 shadowMapSize, float shadowIntensity, float shadowBias, float shadowRadius, vec4 shadowCoord, float shadowCameraNear, float shadowCameraFar ) {
		float shadow = 1.0;
		vec3 lightToPosition = shadowCoord.xyz;
		vec3 absVec = abs( lightToPosition );
		float viewSpaceZ = max( max( absVec.x, absVec.y ), absVec.z );
		if ( viewSpaceZ - shadowCameraFar <= 0.0 && viewSpaceZ - shadowCameraNear >= 0.0 ) {
			float dp = ( shadowCameraFar * ( viewSpaceZ - shadowCameraNear ) ) / ( viewSpaceZ * ( shadowCameraFar - shadowCameraNear ) );
			dp += shadowBias;
			vec3 bd3D = normalize( lightToPosition );
			float depth = textureCube( shadowMap, bd3D ).r;
			#ifdef USE_REVERSED_DEPTH_BUFFER
				depth = 1.0 - depth;
			#endif
			shadow = step( dp, depth );
		}
		return mix( 1.0, shadow, shadowIntensity );
	}
	#endif
	#endif
#endif`,rI=`#if NUM_SPOT_LIGHT_COORDS > 0
	uniform mat4 spotLightMatrix[ NUM_SPOT_LIGHT_COORDS ];
	varying vec4 vSpotLightCoord[ NUM_SPOT_LIGHT_COORDS ];
#endif
#ifdef USE_SHADOWMAP
	#if NUM_SUN_LIGHT_SHADOWS > 0
		varying vec4 vSunShadowWorldPosition;
		varying vec3 vSunShadowWorldNormal;
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
		uniform mat4 directionalShadowMatrix[ NUM_DIR_LIGHT_SHADOWS ];
		varying vec4 vDirectionalShadowCoord[ NUM_DIR_LIGHT_SHADOWS ];
		struct DirectionalLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform DirectionalLightShadow directionalLightShadows[ NUM_DIR_LIGHT_SHADOWS ];
	#endif
	#if NUM_SPOT_LIGHT_SHADOWS > 0
		struct SpotLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
		};
		uniform SpotLightShadow spotLightShadows[ NUM_SPOT_LIGHT_SHADOWS ];
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
		uniform mat4 pointShadowMatrix[ NUM_POINT_LIGHT_SHADOWS ];
		varying vec4 vPointShadowCoord[ NUM_POINT_LIGHT_SHADOWS ];
		struct PointLightShadow {
			float shadowIntensity;
			float shadowBias;
			float shadowNormalBias;
			float shadowRadius;
			vec2 shadowMapSize;
			float shadowCameraNear;
			float shadowCameraFar;
		};
		uniform PointLightShadow pointLightShadows[ NUM_POINT_LIGHT_SHADOWS ];
	#endif
#endif`,sI=`#if ( defined( USE_SHADOWMAP ) && ( NUM_DIR_LIGHT_SHADOWS > 0 || NUM_SUN_LIGHT_SHADOWS > 0 || NUM_POINT_LIGHT_SHADOWS > 0 ) ) || ( NUM_SPOT_LIGHT_COORDS > 0 )
	#ifdef HAS_NORMAL
		vec3 shadowWorldNormal = transformNormalByInverseViewMatrix( transformedNormal, viewMatrix );
	#else
		vec3 shadowWorldNormal = vec3( 0.0 );
	#endif
	vec4 shadowWorldPosition;
#endif
#if defined( USE_SHADOWMAP )
	#if NUM_SUN_LIGHT_SHADOWS > 0
		vSunShadowWorldPosition = vec4( worldPosition.xyz, - mvPosition.z );
		vSunShadowWorldNormal = shadowWorldNormal;
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_DIR_LIGHT_SHADOWS; i ++ ) {
			shadowWorldPosition = worldPosition + vec4( shadowWorldNormal * directionalLightShadows[ i ].shadowNormalBias, 0 );
			vDirectionalShadowCoord[ i ] = directionalShadowMatrix[ i ] * shadowWorldPosition;
		}
		#pragma unroll_loop_end
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0
		#pragma unroll_loop_start
		for ( int i = 0; i < NUM_POINT_LIGHT_SHADOWS; i ++ ) {
			shadowWorldPosition = worldPosition + vec4( shadowWorldNormal * pointLightShadows[ i ].shadowNormalBias, 0 );
			vPointShadowCoord[ i ] = pointShadowMatrix[ i ] * shadowWorldPosition;
		}
		#pragma unroll_loop_end
	#endif
#endif
#if NUM_SPOT_LIGHT_COORDS > 0
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SPOT_LIGHT_COORDS; i ++ ) {
		shadowWorldPosition = worldPosition;
		#if ( defined( USE_SHADOWMAP ) && UNROLLED_LOOP_INDEX < NUM_SPOT_LIGHT_SHADOWS )
			shadowWorldPosition.xyz += shadowWorldNormal * spotLightShadows[ i ].shadowNormalBias;
		#endif
		vSpotLightCoord[ i ] = spotLightMatrix[ i ] * shadowWorldPosition;
	}
	#pragma unroll_loop_end
#endif`,oI=`float getShadowMask() {
	float shadow = 1.0;
	#ifdef USE_SHADOWMAP
	#if NUM_SUN_LIGHT_SHADOWS > 0
	SunLightShadow sunLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SUN_LIGHT_SHADOWS; i ++ ) {
		sunLight = sunLightShadows[ i ];
		shadow *= receiveShadow ? getSunShadow( sunShadowMap[ i ], sunLight, UNROLLED_LOOP_INDEX ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#if NUM_DIR_LIGHT_SHADOWS > 0
	DirectionalLightShadow directionalLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_DIR_LIGHT_SHADOWS; i ++ ) {
		directionalLight = directionalLightShadows[ i ];
		shadow *= receiveShadow ? getShadow( directionalShadowMap[ i ], directionalLight.shadowMapSize, directionalLight.shadowIntensity, directionalLight.shadowBias, directionalLight.shadowRadius, vDirectionalShadowCoord[ i ] ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#if NUM_SPOT_LIGHT_SHADOWS > 0
	SpotLightShadow spotLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_SPOT_LIGHT_SHADOWS; i ++ ) {
		spotLight = spotLightShadows[ i ];
		shadow *= receiveShadow ? getShadow( spotShadowMap[ i ], spotLight.shadowMapSize, spotLight.shadowIntensity, spotLight.shadowBias, spotLight.shadowRadius, vSpotLightCoord[ i ] ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#if NUM_POINT_LIGHT_SHADOWS > 0 && ( defined( SHADOWMAP_TYPE_PCF ) || defined( SHADOWMAP_TYPE_BASIC ) )
	PointLightShadow pointLight;
	#pragma unroll_loop_start
	for ( int i = 0; i < NUM_POINT_LIGHT_SHADOWS; i ++ ) {
		pointLight = pointLightShadows[ i ];
		shadow *= receiveShadow ? getPointShadow( pointShadowMap[ i ], pointLight.shadowMapSize, pointLight.shadowIntensity, pointLight.shadowBias, pointLight.shadowRadius, vPointShadowCoord[ i ], pointLight.shadowCameraNear, pointLight.shadowCameraFar ) : 1.0;
	}
	#pragma unroll_loop_end
	#endif
	#endif
	return shadow;
}`,aI=`#ifdef USE_SKINNING
	mat4 boneMatX = getBoneMatrix( skinIndex.x );
	mat4 boneMatY = getBoneMatrix( skinIndex.y );
	mat4 boneMatZ = getBoneMatrix( skinIndex.z );
	mat4 boneMatW = getBoneMatrix( skinIndex.w );
#endif`,lI=`#ifdef USE_SKINNING
	uniform mat4 bindMatrix;
	uniform mat4 bindMatrixInverse;
	uniform highp sampler2D boneTexture;
	mat4 getBoneMatrix( const in float i ) {
		int size = textureSize( boneTexture, 0 ).x;
		int j = int( i ) * 4;
		int x = j % size;
		int y = j / size;
		vec4 v1 = texelFetch( boneTexture, ivec2( x, y ), 0 );
		vec4 v2 = texelFetch( boneTexture, ivec2( x + 1, y ), 0 );
		vec4 v3 = texelFetch( boneTexture, ivec2( x + 2, y ), 0 );
		vec4 v4 = texelFetch( boneTexture, ivec2( x + 3, y ), 0 );
		return mat4( v1, v2, v3, v4 );
	}
#endif`,cI=`#ifdef USE_SKINNING
	vec4 skinVertex = bindMatrix * vec4( transformed, 1.0 );
	vec4 skinned = vec4( 0.0 );
	skinned += boneMatX * skinVertex * skinWeight.x;
	skinned += boneMatY * skinVertex * skinWeight.y;
	skinned += boneMatZ * skinVertex * skinWeight.z;
	skinned += boneMatW * skinVertex * skinWeight.w;
	transformed = ( bindMatrixInverse * skinned ).xyz;
#endif`,uI=`#ifdef USE_SKINNING
	mat4 skinMatrix = mat4( 0.0 );
	skinMatrix += skinWeight.x * boneMatX;
	skinMatrix += skinWeight.y * boneMatY;
	skinMatrix += skinWeight.z * boneMatZ;
	skinMatrix += skinWeight.w * boneMatW;
	skinMatrix = bindMatrixInverse * skinMatrix * bindMatrix;
	objectNormal = vec4( skinMatrix * vec4( objectNormal, 0.0 ) ).xyz;
	#ifdef USE_TANGENT
		objectTangent = vec4( skinMatrix * vec4( objectTangent, 0.0 ) ).xyz;
	#endif
#endif`,hI=`float specularStrength;
#ifdef USE_SPECULARMAP
	vec4 texelSpecular = texture2D( specularMap, vSpecularMapUv );
	specularStrength = texelSpecular.r;
#else
	specularStrength = 1.0;
#endif`,fI=`#ifdef USE_SPECULARMAP
	uniform sampler2D specularMap;
#endif`,dI=`#if defined( TONE_MAPPING )
	gl_FragColor.rgb = toneMapping( gl_FragColor.rgb );
#endif`,pI=`#ifndef saturate
#define saturate( a ) clamp( a, 0.0, 1.0 )
#endif
uniform float toneMappingExposure;
vec3 LinearToneMapping( vec3 color ) {
	return saturate( toneMappingExposure * color );
}
vec3 ReinhardToneMapping( vec3 color ) {
	color *= toneMappingExposure;
	return saturate( color / ( vec3( 1.0 ) + color ) );
}
vec3 CineonToneMapping( vec3 color ) {
	color *= toneMappingExposure;
	color = max( vec3( 0.0 ), color - 0.004 );
	return pow( ( color * ( 6.2 * color + 0.5 ) ) / ( color * ( 6.2 * color + 1.7 ) + 0.06 ), vec3( 2.2 ) );
}
vec3 RRTAndODTFit( vec3 v ) {
	vec3 a = v * ( v + 0.0245786 ) - 0.000090537;
	vec3 b = v * ( 0.983729 * v + 0.4329510 ) + 0.238081;
	return a / b;
}
vec3 ACESFilmicToneMapping( vec3 color ) {
	const mat3 ACESInputMat = mat3(
		vec3( 0.59719, 0.07600, 0.02840 ),		vec3( 0.35458, 0.90834, 0.13383 ),
		vec3( 0.04823, 0.01566, 0.83777 )
	);
	const mat3 ACESOutputMat = mat3(
		vec3(  1.60475, -0.10208, -0.00327 ),		vec3( -0.53108,  1.10813, -0.07276 ),
		vec3( -0.07367, -0.00605,  1.07602 )
	);
	color *= toneMappingExposure / 0.6;
	color = ACESInputMat * color;
	color = RRTAndODTFit( color );
	color = ACESOutputMat * color;
	return saturate( color );
}
const mat3 LINEAR_REC2020_TO_LINEAR_SRGB = mat3(
	vec3( 1.6605, - 0.1246, - 0.0182 ),
	vec3( - 0.5876, 1.1329, - 0.1006 ),
	vec3( - 0.0728, - 0.0083, 1.1187 )
);
const mat3 LINEAR_SRGB_TO_LINEAR_REC2020 = mat3(
	vec3( 0.6274, 0.0691, 0.0164 ),
	vec3( 0.3293, 0.9195, 0.0880 ),
	vec3( 0.0433, 0.0113, 0.8956 )
);
vec3 agxDefaultContrastApprox( vec3 x ) {
	vec3 x2 = x * x;
	vec3 x4 = x2 * x2;
	return + 15.5 * x4 * x2
		- 40.14 * x4 * x
		+ 31.96 * x4
		- 6.868 * x2 * x
		+ 0.4298 * x2
		+ 0.1191 * x
		- 0.00232;
}
vec3 AgXToneMapping( vec3 color ) {
	const mat3 AgXInsetMatrix = mat3(
		vec3( 0.856627153315983, 0.137318972929847, 0.11189821299995 ),
		vec3( 0.0951212405381588, 0.761241990602591, 0.0767994186031903 ),
		vec3( 0.0482516061458583, 0.101439036467562, 0.811302368396859 )
	);
	const mat3 AgXOutsetMatrix = mat3(
		vec3( 1.1271005818144368, - 0.1413297634984383, - 0.14132976349843826 ),
		vec3( - 0.11060664309660323, 1.157823702216272, - 0.11060664309660294 ),
		vec3( - 0.016493938717834573, - 0.016493938717834257, 1.2519364065950405 )
	);
	const float AgxMinEv = - 12.47393;	const float AgxMaxEv = 4.026069;
	color *= toneMappingExposure;
	color = LINEAR_SRGB_TO_LINEAR_REC2020 * color;
	color = AgXInsetMatrix * color;
	color = max( color, 1e-10 );	color = log2( color );
	color = ( color - AgxMinEv ) / ( AgxMaxEv - AgxMinEv );
	color = clamp( color, 0.0, 1.0 );
	color = agxDefaultContrastApprox( color );
	color = AgXOutsetMatrix * color;
	color = pow( max( vec3( 0.0 ), color ), vec3( 2.2 ) );
	color = LINEAR_REC2020_TO_LINEAR_SRGB * color;
	color = clamp( color, 0.0, 1.0 );
	return color;
}
vec3 NeutralToneMapping( vec3 color ) {
	const float StartCompression = 0.8 - 0.04;
	const float Desaturation = 0.15;
	color *= toneMappingExposure;
	float x = min( color.r, min( color.g, color.b ) );
	float offset = x < 0.08 ? x - 6.25 * x * x : 0.04;
	color -= offset;
	float peak = max( color.r, max( color.g, color.b ) );
	if ( peak < StartCompression ) return color;
	float d = 1. - StartCompression;
	float newPeak = 1. - d * d / ( peak + d - StartCompression );
	color *= newPeak / peak;
	float g = 1. - 1. / ( Desaturation * ( peak - newPeak ) + 1. );
	return mix( color, vec3( newPeak ), g );
}
vec3 CustomToneMapping( vec3 color ) { return color; }`,mI=`#ifdef USE_TRANSMISSION
	material.transmission = transmission;
	material.transmissionAlpha = 1.0;
	material.thickness = thickness;
	material.attenuationDistance = attenuationDistance;
	material.attenuationColor = attenuationColor;
	#ifdef USE_TRANSMISSIONMAP
		material.transmission *= texture2D( transmissionMap, vTransmissionMapUv ).r;
	#endif
	#ifdef USE_THICKNESSMAP
		material.thickness *= texture2D( thicknessMap, vThicknessMapUv ).g;
	#endif
	vec3 pos = vWorldPosition;
	vec3 v = normalize( cameraPosition - pos );
	vec3 n = transformNormalByInverseViewMatrix( normal, viewMatrix );
	vec4 transmitted = getIBLVolumeRefraction(
		n, v, material.roughness, material.diffuseContribution, material.specularColorBlended, material.specularF90,
		pos, modelMatrix, viewMatrix, projectionMatrix, material.dispersion, material.ior, material.thickness,
		material.attenuationColor, material.attenuationDistance );
	material.transmissionAlpha = mix( material.transmissionAlpha, transmitted.a, material.transmission );
	totalDiffuse = mix( totalDiffuse, transmitted.rgb, material.transmission );
#endif`,gI=`#ifdef USE_TRANSMISSION
	uniform float transmission;
	uniform float thickness;
	uniform float attenuationDistance;
	uniform vec3 attenuationColor;
	#ifdef USE_TRANSMISSIONMAP
		uniform sampler2D transmissionMap;
	#endif
	#ifdef USE_THICKNESSMAP
		uniform sampler2D thicknessMap;
	#endif
	uniform vec2 transmissionSamplerSize;
	uniform sampler2D transmissionSamplerMap;
	uniform mat4 modelMatrix;
	uniform mat4 projectionMatrix;
	varying vec3 vWorldPosition;
	float w0( float a ) {
		return ( 1.0 / 6.0 ) * ( a * ( a * ( - a + 3.0 ) - 3.0 ) + 1.0 );
	}
	float w1( float a ) {
		return ( 1.0 / 6.0 ) * ( a *  a * ( 3.0 * a - 6.0 ) + 4.0 );
	}
	float w2( float a ){
		return ( 1.0 / 6.0 ) * ( a * ( a * ( - 3.0 * a + 3.0 ) + 3.0 ) + 1.0 );
	}
	float w3( float a ) {
		return ( 1.0 / 6.0 ) * ( a * a * a );
	}
	float g0( float a ) {
		return w0( a ) + w1( a );
	}
	float g1( float a ) {
		return w2( a ) + w3( a );
	}
	float h0( float a ) {
		return - 1.0 + w1( a ) / ( w0( a ) + w1( a ) );
	}
	float h1( float a ) {
		return 1.0 + w3( a ) / ( w2( a ) + w3( a ) );
	}
	vec4 bicubic( sampler2D tex, vec2 uv, vec4 texelSize, float lod ) {
		uv = uv * texelSize.zw + 0.5;
		vec2 iuv = floor( uv );
		vec2 fuv = fract( uv );
		float g0x = g0( fuv.x );
		float g1x = g1( fuv.x );
		float h0x = h0( fuv.x );
		float h1x = h1( fuv.x );
		float h0y = h0( fuv.y );
		float h1y = h1( fuv.y );
		vec2 p0 = ( vec2( iuv.x + h0x, iuv.y + h0y ) - 0.5 ) * texelSize.xy;
		vec2 p1 = ( vec2( iuv.x + h1x, iuv.y + h0y ) - 0.5 ) * texelSize.xy;
		vec2 p2 = ( vec2( iuv.x + h0x, iuv.y + h1y ) - 0.5 ) * texelSize.xy;
		vec2 p3 = ( vec2( iuv.x + h1x, iuv.y + h1y ) - 0.5 ) * texelSize.xy;
		return g0( fuv.y ) * ( g0x * textureLod( tex, p0, lod ) + g1x * textureLod( tex, p1, lod ) ) +
			g1( fuv.y ) * ( g0x * textureLod( tex, p2, lod ) + g1x * textureLod( tex, p3, lod ) );
	}
	vec4 textureBicubic( sampler2D sampler, vec2 uv, float lod ) {
		vec2 fLodSize = vec2( textureSize( sampler, int( lod ) ) );
		vec2 cLodSize = vec2( textureSize( sampler, int( lod + 1.0 ) ) );
		vec2 fLodSizeInv = 1.0 / fLodSize;
		vec2 cLodSizeInv = 1.0 / cLodSize;
		vec4 fSample = bicubic( sampler, uv, vec4( fLodSizeInv, fLodSize ), floor( lod ) );
		vec4 cSample = bicubic( sampler, uv, vec4( cLodSizeInv, cLodSize ), ceil( lod ) );
		return mix( fSample, cSample, fract( lod ) );
	}
	vec3 getVolumeTransmissionRay( const in vec3 n, const in vec3 v, const in float thickness, const in float ior, const in mat4 modelMatrix ) {
		vec3 refractionVector = refract( - v, normalize( n ), 1.0 / ior );
		vec3 modelScale;
		modelScale.x = length( vec3( modelMatrix[ 0 ].xyz ) );
		modelScale.y = length( vec3( modelMatrix[ 1 ].xyz ) );
		modelScale.z = length( vec3( modelMatrix[ 2 ].xyz ) );
		return normalize( refractionVector ) * thickness * modelScale;
	}
	float applyIorToRoughness( const in float roughness, const in float ior ) {
		return roughness * clamp( ior * 2.0 - 2.0, 0.0, 1.0 );
	}
	vec4 getTransmissionSample( const in vec2 fragCoord, const in float roughness, const in float ior ) {
		float lod = log2( transmissionSamplerSize.x ) * applyIorToRoughness( roughness, ior );
		return textureBicubic( transmissionSamplerMap, fragCoord.xy, lod );
	}
	vec3 volumeAttenuation( const in float transmissionDistance, const in vec3 attenuationColor, const in float attenuationDistance ) {
		if ( isinf( attenuationDistance ) ) {
			return vec3( 1.0 );
		} else {
			vec3 attenuationCoefficient = -log( attenuationColor ) / attenuationDistance;
			vec3 transmittance = exp( - attenuationCoefficient * transmissionDistance );			return transmittance;
		}
	}
	vec4 getIBLVolumeRefraction( const in vec3 n, const in vec3 v, const in float roughness, const in vec3 diffuseColor,
		const in vec3 specularColor, const in float specularF90, const in vec3 position, const in mat4 modelMatrix,
		const in mat4 viewMatrix, const in mat4 projMatrix, const in float dispersion, const in float ior, const in float thickness,
		const in vec3 attenuationColor, const in float attenuationDistance ) {
		vec4 transmittedLight;
		vec3 transmittance;
		#ifdef USE_DISPERSION
			float halfSpread = ( ior - 1.0 ) * 0.025 * dispersion;
			vec3 iors = vec3( ior - halfSpread, ior, ior + halfSpread );
			for ( int i = 0; i < 3; i ++ ) {
				vec3 transmissionRay = getVolumeTransmissionRay( n, v, thickness, iors[ i ], modelMatrix );
				vec3 refractedRayExit = position + transmissionRay;
				vec4 ndcPos = projMatrix * viewMatrix * vec4( refractedRayExit, 1.0 );
				vec2 refractionCoords = ndcPos.xy / ndcPos.w;
				refractionCoords += 1.0;
				refractionCoords /= 2.0;
				vec4 transmissionSample = getTransmissionSample( refractionCoords, roughness, iors[ i ] );
				transmittedLight[ i ] = transmissionSample[ i ];
				transmittedLight.a += transmissionSample.a;
				transmittance[ i ] = diffuseColor[ i ] * volumeAttenuation( length( transmissionRay ), attenuationColor, attenuationDistance )[ i ];
			}
			transmittedLight.a /= 3.0;
		#else
			vec3 transmissionRay = getVolumeTransmissionRay( n, v, thickness, ior, modelMatrix );
			vec3 refractedRayExit = position + transmissionRay;
			vec4 ndcPos = projMatrix * viewMatrix * vec4( refractedRayExit, 1.0 );
			vec2 refractionCoords = ndcPos.xy / ndcPos.w;
			refractionCoords += 1.0;
			refractionCoords /= 2.0;
			transmittedLight = getTransmissionSample( refractionCoords, roughness, ior );
			transmittance = diffuseColor * volumeAttenuation( length( transmissionRay ), attenuationColor, attenuationDistance );
		#endif
		vec3 attenuatedColor = transmittance * transmittedLight.rgb;
		vec3 F = EnvironmentBRDF( n, v, specularColor, specularF90, roughness );
		float transmittanceFactor = ( transmittance.r + transmittance.g + transmittance.b ) / 3.0;
		return vec4( ( 1.0 - F ) * attenuatedColor, 1.0 - ( 1.0 - transmittedLight.a ) * transmittanceFactor );
	}
#endif`,yI=`#if defined( USE_UV ) || defined( USE_ANISOTROPY )
	varying vec2 vUv;
#endif
#ifdef USE_MAP
	varying vec2 vMapUv;
#endif
#ifdef USE_ALPHAMAP
	varying vec2 vAlphaMapUv;
#endif
#ifdef USE_LIGHTMAP
	varying vec2 vLightMapUv;
#endif
#ifdef USE_AOMAP
	varying vec2 vAoMapUv;
#endif
#ifdef USE_BUMPMAP
	varying vec2 vBumpMapUv;
#endif
#ifdef USE_NORMALMAP
	varying vec2 vNormalMapUv;
#endif
#ifdef USE_EMISSIVEMAP
	varying vec2 vEmissiveMapUv;
#endif
#ifdef USE_METALNESSMAP
	varying vec2 vMetalnessMapUv;
#endif
#ifdef USE_ROUGHNESSMAP
	varying vec2 vRoughnessMapUv;
#endif
#ifdef USE_DIFFUSE_ROUGHNESSMAP
	varying vec2 vDiffuseRoughnessMapUv;
#endif
#ifdef USE_ANISOTROPYMAP
	varying vec2 vAnisotropyMapUv;
#endif
#ifdef USE_CLEARCOATMAP
	varying vec2 vClearcoatMapUv;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	varying vec2 vClearcoatNormalMapUv;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	varying vec2 vClearcoatRoughnessMapUv;
#endif
#ifdef USE_IRIDESCENCEMAP
	varying vec2 vIridescenceMapUv;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	varying vec2 vIridescenceThicknessMapUv;
#endif
#ifdef USE_SHEEN_COLORMAP
	varying vec2 vSheenColorMapUv;
#endif
#ifdef USE_SHEEN_ROUGHNESSMAP
	varying vec2 vSheenRoughnessMapUv;
#endif
#ifdef USE_SPECULARMAP
	varying vec2 vSpecularMapUv;
#endif
#ifdef USE_SPECULAR_COLORMAP
	varying vec2 vSpecularColorMapUv;
#endif
#ifdef USE_SPECULAR_INTENSITYMAP
	varying vec2 vSpecularIntensityMapUv;
#endif
#ifdef USE_TRANSMISSIONMAP
	uniform mat3 transmissionMapTransform;
	varying vec2 vTransmissionMapUv;
#endif
#ifdef USE_THICKNESSMAP
	uniform mat3 thicknessMapTransform;
	varying vec2 vThicknessMapUv;
#endif`,_I=`#if defined( USE_UV ) || defined( USE_ANISOTROPY )
	varying vec2 vUv;
#endif
#ifdef USE_MAP
	uniform mat3 mapTransform;
	varying vec2 vMapUv;
#endif
#ifdef USE_ALPHAMAP
	uniform mat3 alphaMapTransform;
	varying vec2 vAlphaMapUv;
#endif
#ifdef USE_LIGHTMAP
	uniform mat3 lightMapTransform;
	varying vec2 vLightMapUv;
#endif
#ifdef USE_AOMAP
	uniform mat3 aoMapTransform;
	varying vec2 vAoMapUv;
#endif
#ifdef USE_BUMPMAP
	uniform mat3 bumpMapTransform;
	varying vec2 vBumpMapUv;
#endif
#ifdef USE_NORMALMAP
	uniform mat3 normalMapTransform;
	varying vec2 vNormalMapUv;
#endif
#ifdef USE_DISPLACEMENTMAP
	uniform mat3 displacementMapTransform;
	varying vec2 vDisplacementMapUv;
#endif
#ifdef USE_EMISSIVEMAP
	uniform mat3 emissiveMapTransform;
	varying vec2 vEmissiveMapUv;
#endif
#ifdef USE_METALNESSMAP
	uniform mat3 metalnessMapTransform;
	varying vec2 vMetalnessMapUv;
#endif
#ifdef USE_ROUGHNESSMAP
	uniform mat3 roughnessMapTransform;
	varying vec2 vRoughnessMapUv;
#endif
#ifdef USE_DIFFUSE_ROUGHNESSMAP
	uniform mat3 diffuseRoughnessMapTransform;
	varying vec2 vDiffuseRoughnessMapUv;
#endif
#ifdef USE_ANISOTROPYMAP
	uniform mat3 anisotropyMapTransform;
	varying vec2 vAnisotropyMapUv;
#endif
#ifdef USE_CLEARCOATMAP
	uniform mat3 clearcoatMapTransform;
	varying vec2 vClearcoatMapUv;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	uniform mat3 clearcoatNormalMapTransform;
	varying vec2 vClearcoatNormalMapUv;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	uniform mat3 clearcoatRoughnessMapTransform;
	varying vec2 vClearcoatRoughnessMapUv;
#endif
#ifdef USE_SHEEN_COLORMAP
	uniform mat3 sheenColorMapTransform;
	varying vec2 vSheenColorMapUv;
#endif
#ifdef USE_SHEEN_ROUGHNESSMAP
	uniform mat3 sheenRoughnessMapTransform;
	varying vec2 vSheenRoughnessMapUv;
#endif
#ifdef USE_IRIDESCENCEMAP
	uniform mat3 iridescenceMapTransform;
	varying vec2 vIridescenceMapUv;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	uniform mat3 iridescenceThicknessMapTransform;
	varying vec2 vIridescenceThicknessMapUv;
#endif
#ifdef USE_SPECULARMAP
	uniform mat3 specularMapTransform;
	varying vec2 vSpecularMapUv;
#endif
#ifdef USE_SPECULAR_COLORMAP
	uniform mat3 specularColorMapTransform;
	varying vec2 vSpecularColorMapUv;
#endif
#ifdef USE_SPECULAR_INTENSITYMAP
	uniform mat3 specularIntensityMapTransform;
	varying vec2 vSpecularIntensityMapUv;
#endif
#ifdef USE_TRANSMISSIONMAP
	uniform mat3 transmissionMapTransform;
	varying vec2 vTransmissionMapUv;
#endif
#ifdef USE_THICKNESSMAP
	uniform mat3 thicknessMapTransform;
	varying vec2 vThicknessMapUv;
#endif`,xI=`#if defined( USE_UV ) || defined( USE_ANISOTROPY )
	vUv = vec3( uv, 1 ).xy;
#endif
#ifdef USE_MAP
	vMapUv = ( mapTransform * vec3( MAP_UV, 1 ) ).xy;
#endif
#ifdef USE_ALPHAMAP
	vAlphaMapUv = ( alphaMapTransform * vec3( ALPHAMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_LIGHTMAP
	vLightMapUv = ( lightMapTransform * vec3( LIGHTMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_AOMAP
	vAoMapUv = ( aoMapTransform * vec3( AOMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_BUMPMAP
	vBumpMapUv = ( bumpMapTransform * vec3( BUMPMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_NORMALMAP
	vNormalMapUv = ( normalMapTransform * vec3( NORMALMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_DISPLACEMENTMAP
	vDisplacementMapUv = ( displacementMapTransform * vec3( DISPLACEMENTMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_EMISSIVEMAP
	vEmissiveMapUv = ( emissiveMapTransform * vec3( EMISSIVEMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_METALNESSMAP
	vMetalnessMapUv = ( metalnessMapTransform * vec3( METALNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_ROUGHNESSMAP
	vRoughnessMapUv = ( roughnessMapTransform * vec3( ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_DIFFUSE_ROUGHNESSMAP
	vDiffuseRoughnessMapUv = ( diffuseRoughnessMapTransform * vec3( DIFFUSE_ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_ANISOTROPYMAP
	vAnisotropyMapUv = ( anisotropyMapTransform * vec3( ANISOTROPYMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_CLEARCOATMAP
	vClearcoatMapUv = ( clearcoatMapTransform * vec3( CLEARCOATMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_CLEARCOAT_NORMALMAP
	vClearcoatNormalMapUv = ( clearcoatNormalMapTransform * vec3( CLEARCOAT_NORMALMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_CLEARCOAT_ROUGHNESSMAP
	vClearcoatRoughnessMapUv = ( clearcoatRoughnessMapTransform * vec3( CLEARCOAT_ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_IRIDESCENCEMAP
	vIridescenceMapUv = ( iridescenceMapTransform * vec3( IRIDESCENCEMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_IRIDESCENCE_THICKNESSMAP
	vIridescenceThicknessMapUv = ( iridescenceThicknessMapTransform * vec3( IRIDESCENCE_THICKNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SHEEN_COLORMAP
	vSheenColorMapUv = ( sheenColorMapTransform * vec3( SHEEN_COLORMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SHEEN_ROUGHNESSMAP
	vSheenRoughnessMapUv = ( sheenRoughnessMapTransform * vec3( SHEEN_ROUGHNESSMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SPECULARMAP
	vSpecularMapUv = ( specularMapTransform * vec3( SPECULARMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SPECULAR_COLORMAP
	vSpecularColorMapUv = ( specularColorMapTransform * vec3( SPECULAR_COLORMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_SPECULAR_INTENSITYMAP
	vSpecularIntensityMapUv = ( specularIntensityMapTransform * vec3( SPECULAR_INTENSITYMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_TRANSMISSIONMAP
	vTransmissionMapUv = ( transmissionMapTransform * vec3( TRANSMISSIONMAP_UV, 1 ) ).xy;
#endif
#ifdef USE_THICKNESSMAP
	vThicknessMapUv = ( thicknessMapTransform * vec3( THICKNESSMAP_UV, 1 ) ).xy;
#endif`,vI=`#if defined( USE_ENVMAP ) || defined( DISTANCE ) || defined ( USE_SHADOWMAP ) || defined ( USE_TRANSMISSION ) || NUM_SPOT_LIGHT_COORDS > 0
	vec4 worldPosition = vec4( transformed, 1.0 );
	#ifdef USE_BATCHING
		worldPosition = batchingMatrix * worldPosition;
	#endif
	#ifdef USE_INSTANCING
		worldPosition = instanceMatrix * worldPosition;
	#endif
	worldPosition = modelMatrix * worldPosition;
#endif`,bI=`varying vec2 vUv;
uniform mat3 uvTransform;
void main() {
	vUv = ( uvTransform * vec3( uv, 1 ) ).xy;
	gl_Position = vec4( position.xy, 1.0, 1.0 );
}`,SI=`uniform sampler2D t2D;
uniform float backgroundIntensity;
varying vec2 vUv;
void main() {
	vec4 texColor = texture2D( t2D, vUv );
	#ifdef DECODE_VIDEO_TEXTURE
		texColor = vec4( mix( pow( texColor.rgb * 0.9478672986 + vec3( 0.0521327014 ), vec3( 2.4 ) ), texColor.rgb * 0.0773993808, vec3( lessThanEqual( texColor.rgb, vec3( 0.04045 ) ) ) ), texColor.w );
	#endif
	texColor.rgb *= backgroundIntensity;
	gl_FragColor = texColor;
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,MI=`varying vec3 vWorldDirection;
#include <common>
void main() {
	vWorldDirection = transformDirection( position, modelMatrix );
	#include <begin_vertex>
	#include <project_vertex>
	gl_Position.z = gl_Position.w;
}`,EI=`uniform float backgroundBlurriness;
uniform float backgroundIntensity;
uniform mat3 backgroundRotation;
varying vec3 vWorldDirection;
#include <envmap_common_pars_fragment>
void main() {
	#ifdef ENVMAP_TYPE_PMREM
		vec4 texColor = textureLod( envMap, backgroundRotation * vWorldDirection, roughnessToMip( backgroundBlurriness ) );
	#else
		vec4 texColor = textureCube( envMap, backgroundRotation * vWorldDirection );
	#endif
	texColor.rgb *= backgroundIntensity;
	gl_FragColor = texColor;
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,wI=`varying vec3 vWorldDirection;
#include <common>
void main() {
	vWorldDirection = transformDirection( position, modelMatrix );
	#include <begin_vertex>
	#include <project_vertex>
	gl_Position.z = gl_Position.w;
}`,AI=`uniform samplerCube tCube;
uniform float tFlip;
uniform float opacity;
varying vec3 vWorldDirection;
void main() {
	vec4 texColor = textureCube( tCube, vec3( tFlip * vWorldDirection.x, vWorldDirection.yz ) );
	gl_FragColor = texColor;
	gl_FragColor.a *= opacity;
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,TI=`#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
varying vec2 vHighPrecisionZW;
void main() {
	#include <uv_vertex>
	#include <batching_vertex>
	#include <skinbase_vertex>
	#include <morphinstance_vertex>
	#ifdef USE_DISPLACEMENTMAP
		#include <beginnormal_vertex>
		#include <morphnormal_vertex>
		#include <skinnormal_vertex>
	#endif
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vHighPrecisionZW = gl_Position.zw;
}`,RI=`#if DEPTH_PACKING == 3200
	uniform float opacity;
#endif
#include <common>
#include <packing>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
varying vec2 vHighPrecisionZW;
void main() {
	vec4 diffuseColor = vec4( 1.0 );
	#include <clipping_planes_fragment>
	#if DEPTH_PACKING == 3200
		diffuseColor.a = opacity;
	#endif
	#include <map_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <logdepthbuf_fragment>
	#ifdef USE_REVERSED_DEPTH_BUFFER
		float fragCoordZ = vHighPrecisionZW[ 0 ] / vHighPrecisionZW[ 1 ];
	#else
		float fragCoordZ = 0.5 * vHighPrecisionZW[ 0 ] / vHighPrecisionZW[ 1 ] + 0.5;
	#endif
	#if DEPTH_PACKING == 3200
		gl_FragColor = vec4( vec3( 1.0 - fragCoordZ ), opacity );
	#elif DEPTH_PACKING == 3201
		gl_FragColor = packDepthToRGBA( fragCoordZ );
	#elif DEPTH_PACKING == 3202
		gl_FragColor = vec4( packDepthToRGB( fragCoordZ ), 1.0 );
	#elif DEPTH_PACKING == 3203
		gl_FragColor = vec4( packDepthToRG( fragCoordZ ), 0.0, 1.0 );
	#endif
}`,II=`#define DISTANCE
varying vec3 vWorldPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <batching_vertex>
	#include <skinbase_vertex>
	#include <morphinstance_vertex>
	#ifdef USE_DISPLACEMENTMAP
		#include <beginnormal_vertex>
		#include <morphnormal_vertex>
		#include <skinnormal_vertex>
	#endif
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <worldpos_vertex>
	#include <clipping_planes_vertex>
	vWorldPosition = worldPosition.xyz;
}`,CI=`#define DISTANCE
uniform vec3 referencePosition;
uniform float nearDistance;
uniform float farDistance;
varying vec3 vWorldPosition;
#include <common>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( 1.0 );
	#include <clipping_planes_fragment>
	#include <map_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	float dist = length( vWorldPosition - referencePosition );
	dist = ( dist - nearDistance ) / ( farDistance - nearDistance );
	dist = saturate( dist );
	gl_FragColor = vec4( dist, 0.0, 0.0, 1.0 );
}`,NI=`varying vec3 vWorldDirection;
#include <common>
void main() {
	vWorldDirection = transformDirection( position, modelMatrix );
	#include <begin_vertex>
	#include <project_vertex>
}`,PI=`uniform sampler2D tEquirect;
varying vec3 vWorldDirection;
#include <common>
void main() {
	vec3 direction = normalize( vWorldDirection );
	vec2 sampleUV = equirectUv( direction );
	gl_FragColor = texture2D( tEquirect, sampleUV );
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
}`,LI=`uniform float scale;
attribute float lineDistance;
varying float vLineDistance;
#include <common>
#include <uv_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	vLineDistance = scale * lineDistance;
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <fog_vertex>
}`,DI=`uniform vec3 diffuse;
uniform float opacity;
uniform float dashSize;
uniform float totalSize;
varying float vLineDistance;
#include <common>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <fog_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	if ( mod( vLineDistance, totalSize ) > dashSize ) {
		discard;
	}
	vec3 outgoingLight = vec3( 0.0 );
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	outgoingLight = diffuseColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
}`,UI=`#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <envmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#if defined ( USE_ENVMAP ) || defined ( USE_SKINNING )
		#include <beginnormal_vertex>
		#include <morphnormal_vertex>
		#include <skinbase_vertex>
		#include <skinnormal_vertex>
		#include <defaultnormal_vertex>
	#endif
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <worldpos_vertex>
	#include <envmap_vertex>
	#include <fog_vertex>
}`,OI=`uniform vec3 diffuse;
uniform float opacity;
#ifndef FLAT_SHADED
	varying vec3 vNormal;
#endif
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_pars_fragment>
#include <fog_pars_fragment>
#include <specularmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <specularmap_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	#ifdef USE_LIGHTMAP
		vec4 lightMapTexel = texture2D( lightMap, vLightMapUv );
		reflectedLight.indirectDiffuse += lightMapTexel.rgb * lightMapIntensity * RECIPROCAL_PI;
	#else
		reflectedLight.indirectDiffuse += vec3( 1.0 );
	#endif
	#include <aomap_fragment>
	reflectedLight.indirectDiffuse *= diffuseColor.rgb;
	vec3 outgoingLight = reflectedLight.indirectDiffuse;
	#include <envmap_fragment>
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,FI=`#define LAMBERT
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <envmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <envmap_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,BI=`#define LAMBERT
uniform vec3 diffuse;
uniform vec3 emissive;
uniform float opacity;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_pars_fragment>
#include <envmap_physical_pars_fragment>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_lambert_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <specularmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <specularmap_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_lambert_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 outgoingLight = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse + totalEmissiveRadiance;
	#include <envmap_fragment>
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,kI=`#define MATCAP
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <color_pars_vertex>
#include <displacementmap_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <fog_vertex>
	vViewPosition = - mvPosition.xyz;
}`,VI=`#define MATCAP
uniform vec3 diffuse;
uniform float opacity;
uniform sampler2D matcap;
varying vec3 vViewPosition;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <fog_pars_fragment>
#include <normal_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	vec3 viewDir = normalize( vViewPosition );
	vec3 x = normalize( vec3( viewDir.z, 0.0, - viewDir.x ) );
	vec3 y = cross( viewDir, x );
	vec2 uv = vec2( dot( x, normal ), dot( y, normal ) ) * 0.495 + 0.5;
	#ifdef USE_MATCAP
		vec4 matcapColor = texture2D( matcap, uv );
	#else
		vec4 matcapColor = vec4( vec3( mix( 0.2, 0.8, uv.y ) ), 1.0 );
	#endif
	vec3 outgoingLight = diffuseColor.rgb * matcapColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,GI=`#define NORMAL
#if defined( FLAT_SHADED ) || defined( USE_BUMPMAP ) || defined( USE_NORMALMAP_TANGENTSPACE )
	varying vec3 vViewPosition;
#endif
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
#if defined( FLAT_SHADED ) || defined( USE_BUMPMAP ) || defined( USE_NORMALMAP_TANGENTSPACE )
	vViewPosition = - mvPosition.xyz;
#endif
}`,zI=`#define NORMAL
uniform float opacity;
#if defined( FLAT_SHADED ) || defined( USE_BUMPMAP ) || defined( USE_NORMALMAP_TANGENTSPACE )
	varying vec3 vViewPosition;
#endif
#include <uv_pars_fragment>
#include <normal_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( 0.0, 0.0, 0.0, opacity );
	#include <clipping_planes_fragment>
	#include <logdepthbuf_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	gl_FragColor = vec4( normalize( normal ) * 0.5 + 0.5, diffuseColor.a );
	#ifdef OPAQUE
		gl_FragColor.a = 1.0;
	#endif
}`,HI=`#define PHONG
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <envmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <envmap_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,WI=`#define PHONG
uniform vec3 diffuse;
uniform vec3 emissive;
uniform vec3 specular;
uniform float shininess;
uniform float opacity;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_pars_fragment>
#include <envmap_physical_pars_fragment>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_phong_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <specularmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <specularmap_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_phong_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 outgoingLight = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse + reflectedLight.directSpecular + reflectedLight.indirectSpecular + totalEmissiveRadiance;
	#include <envmap_fragment>
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,XI=`#define STANDARD
varying vec3 vViewPosition;
#ifdef USE_TRANSMISSION
	varying vec3 vWorldPosition;
#endif
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
#ifdef USE_TRANSMISSION
	vWorldPosition = worldPosition.xyz;
#endif
}`,YI=`#define STANDARD
#ifdef PHYSICAL
	#define IOR
	#define USE_SPECULAR
#endif
uniform vec3 diffuse;
uniform vec3 emissive;
uniform float roughness;
uniform float metalness;
uniform float opacity;
#ifdef IOR
	uniform float ior;
#endif
#ifdef USE_SPECULAR
	uniform float specularIntensity;
	uniform vec3 specularColor;
	#ifdef USE_SPECULAR_COLORMAP
		uniform sampler2D specularColorMap;
	#endif
	#ifdef USE_SPECULAR_INTENSITYMAP
		uniform sampler2D specularIntensityMap;
	#endif
#endif
#ifdef USE_CLEARCOAT
	uniform float clearcoat;
	uniform float clearcoatRoughness;
#endif
#ifdef USE_DIFFUSE_ROUGHNESS
	uniform float diffuseRoughness;
	#ifdef USE_DIFFUSE_ROUGHNESSMAP
		uniform sampler2D diffuseRoughnessMap;
	#endif
#endif
#ifdef USE_DISPERSION
	uniform float dispersion;
#endif
#ifdef USE_RETROREFLECTION
	uniform float retroreflectivity;
#endif
#ifdef USE_IRIDESCENCE
	uniform float iridescence;
	uniform float iridescenceIOR;
	uniform float iridescenceThicknessMinimum;
	uniform float iridescenceThicknessMaximum;
#endif
#ifdef USE_SHEEN
	uniform vec3 sheenColor;
	uniform float sheenRoughness;
	#ifdef USE_SHEEN_COLORMAP
		uniform sampler2D sheenColorMap;
	#endif
	#ifdef USE_SHEEN_ROUGHNESSMAP
		uniform sampler2D sheenRoughnessMap;
	#endif
#endif
#ifdef USE_ANISOTROPY
	uniform vec2 anisotropyVector;
	#ifdef USE_ANISOTROPYMAP
		uniform sampler2D anisotropyMap;
	#endif
#endif
varying vec3 vViewPosition;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <iridescence_fragment>
#include <envmap_common_pars_fragment>
#include <envmap_physical_pars_fragment>
#include <fog_pars_fragment>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_physical_pars_fragment>
#include <transmission_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <clearcoat_pars_fragment>
#include <iridescence_pars_fragment>
#include <roughnessmap_pars_fragment>
#include <metalnessmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <roughnessmap_fragment>
	#include <metalnessmap_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <clearcoat_normal_fragment_begin>
	#include <clearcoat_normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_physical_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 totalDiffuse = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse;
	vec3 totalSpecular = reflectedLight.directSpecular + reflectedLight.indirectSpecular;
	#include <transmission_fragment>
	vec3 outgoingLight = totalDiffuse + totalSpecular + totalEmissiveRadiance;
	#ifdef USE_SHEEN
 
		outgoingLight = outgoingLight + sheenSpecularDirect + sheenSpecularIndirect;
 
 	#endif
	#ifdef USE_CLEARCOAT
		float dotNVcc = saturate( dot( geometryClearcoatNormal, geometryViewDir ) );
		vec3 Fcc = F_Schlick( material.clearcoatF0, material.clearcoatF90, dotNVcc );
		outgoingLight = outgoingLight * ( 1.0 - material.clearcoat * Fcc ) + ( clearcoatSpecularDirect + clearcoatSpecularIndirect ) * material.clearcoat;
	#endif
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,ZI=`#define TOON
varying vec3 vViewPosition;
#include <common>
#include <batching_pars_vertex>
#include <uv_pars_vertex>
#include <displacementmap_pars_vertex>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <normal_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <shadowmap_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <normal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <displacementmap_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	vViewPosition = - mvPosition.xyz;
	#include <worldpos_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,KI=`#define TOON
uniform vec3 diffuse;
uniform vec3 emissive;
uniform float opacity;
#include <common>
#include <dithering_pars_fragment>
#include <color_pars_fragment>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <aomap_pars_fragment>
#include <lightmap_pars_fragment>
#include <emissivemap_pars_fragment>
#include <gradientmap_pars_fragment>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <normal_pars_fragment>
#include <lights_toon_pars_fragment>
#include <shadowmap_pars_fragment>
#include <bumpmap_pars_fragment>
#include <normalmap_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	ReflectedLight reflectedLight = ReflectedLight( vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ), vec3( 0.0 ) );
	vec3 totalEmissiveRadiance = emissive;
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <color_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	#include <normal_fragment_begin>
	#include <normal_fragment_maps>
	#include <emissivemap_fragment>
	#include <lights_toon_fragment>
	#include <lights_fragment_begin>
	#include <lights_fragment_maps>
	#include <lights_fragment_end>
	#include <aomap_fragment>
	vec3 outgoingLight = reflectedLight.directDiffuse + reflectedLight.indirectDiffuse + totalEmissiveRadiance;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
	#include <dithering_fragment>
}`,$I=`uniform float size;
uniform float scale;
#include <common>
#include <color_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
#ifdef USE_POINTS_UV
	varying vec2 vUv;
	uniform mat3 uvTransform;
#endif
void main() {
	#ifdef USE_POINTS_UV
		vUv = ( uvTransform * vec3( uv, 1 ) ).xy;
	#endif
	#include <color_vertex>
	#include <morphinstance_vertex>
	#include <morphcolor_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <project_vertex>
	gl_PointSize = size;
	#ifdef USE_SIZEATTENUATION
		bool isPerspective = isPerspectiveMatrix( projectionMatrix );
		if ( isPerspective ) gl_PointSize *= ( scale / - mvPosition.z );
	#endif
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <worldpos_vertex>
	#include <fog_vertex>
}`,qI=`uniform vec3 diffuse;
uniform float opacity;
#include <common>
#include <color_pars_fragment>
#include <map_particle_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <fog_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	vec3 outgoingLight = vec3( 0.0 );
	#include <logdepthbuf_fragment>
	#include <map_particle_fragment>
	#include <color_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	outgoingLight = diffuseColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
}`,JI=`#include <common>
#include <batching_pars_vertex>
#include <fog_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <shadowmap_pars_vertex>
void main() {
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <project_vertex>
	#include <logdepthbuf_vertex>
	#include <worldpos_vertex>
	#include <shadowmap_vertex>
	#include <fog_vertex>
}`,jI=`uniform vec3 color;
uniform float opacity;
#include <common>
#include <fog_pars_fragment>
#include <bsdfs>
#include <lights_pars_begin>
#include <logdepthbuf_pars_fragment>
#include <shadowmap_pars_fragment>
#include <shadowmask_pars_fragment>
void main() {
	#include <logdepthbuf_fragment>
	gl_FragColor = vec4( color, opacity * ( 1.0 - getShadowMask() ) );
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
	#include <premultiplied_alpha_fragment>
}`,QI=`uniform float rotation;
uniform vec2 center;
#include <common>
#include <uv_pars_vertex>
#include <fog_pars_vertex>
#include <logdepthbuf_pars_vertex>
#include <clipping_planes_pars_vertex>
void main() {
	#include <uv_vertex>
	vec4 mvPosition = modelViewMatrix[ 3 ];
	vec2 scale = vec2( length( modelMatrix[ 0 ].xyz ), length( modelMatrix[ 1 ].xyz ) );
	#ifndef USE_SIZEATTENUATION
		bool isPerspective = isPerspectiveMatrix( projectionMatrix );
		if ( isPerspective ) scale *= - mvPosition.z;
	#endif
	vec2 alignedPosition = ( position.xy - ( center - vec2( 0.5 ) ) ) * scale;
	vec2 rotatedPosition;
	rotatedPosition.x = cos( rotation ) * alignedPosition.x - sin( rotation ) * alignedPosition.y;
	rotatedPosition.y = sin( rotation ) * alignedPosition.x + cos( rotation ) * alignedPosition.y;
	mvPosition.xy += rotatedPosition;
	gl_Position = projectionMatrix * mvPosition;
	#include <logdepthbuf_vertex>
	#include <clipping_planes_vertex>
	#include <fog_vertex>
}`,eC=`uniform vec3 diffuse;
uniform float opacity;
#include <common>
#include <uv_pars_fragment>
#include <map_pars_fragment>
#include <alphamap_pars_fragment>
#include <alphatest_pars_fragment>
#include <alphahash_pars_fragment>
#include <fog_pars_fragment>
#include <logdepthbuf_pars_fragment>
#include <clipping_planes_pars_fragment>
void main() {
	vec4 diffuseColor = vec4( diffuse, opacity );
	#include <clipping_planes_fragment>
	vec3 outgoingLight = vec3( 0.0 );
	#include <logdepthbuf_fragment>
	#include <map_fragment>
	#include <alphamap_fragment>
	#include <alphatest_fragment>
	#include <alphahash_fragment>
	outgoingLight = diffuseColor.rgb;
	#include <opaque_fragment>
	#include <tonemapping_fragment>
	#include <colorspace_fragment>
	#include <fog_fragment>
}`,dt={alphahash_fragment:ST,alphahash_pars_fragment:MT,alphamap_fragment:ET,alphamap_pars_fragment:wT,alphatest_fragment:AT,alphatest_pars_fragment:TT,aomap_fragment:RT,aomap_pars_fragment:IT,batching_pars_vertex:CT,batching_vertex:NT,begin_vertex:PT,beginnormal_vertex:LT,bsdfs:DT,iridescence_fragment:UT,bumpmap_pars_fragment:OT,clipping_planes_fragment:FT,clipping_planes_pars_fragment:BT,clipping_planes_pars_vertex:kT,clipping_planes_vertex:VT,color_fragment:GT,color_pars_fragment:zT,color_pars_vertex:HT,color_vertex:WT,common:XT,defaultnormal_vertex:YT,displacementmap_pars_vertex:ZT,displacementmap_vertex:KT,emissivemap_fragment:$T,emissivemap_pars_fragment:qT,colorspace_fragment:JT,colorspace_pars_fragment:jT,envmap_fragment:QT,envmap_common_pars_fragment:eR,envmap_pars_fragment:tR,envmap_pars_vertex:nR,envmap_physical_pars_fragment:dR,envmap_vertex:iR,fog_vertex:rR,fog_pars_vertex:sR,fog_fragment:oR,fog_pars_fragment:aR,gradientmap_pars_fragment:lR,lightmap_pars_fragment:cR,lights_lambert_fragment:uR,lights_lambert_pars_fragment:hR,lights_pars_begin:fR,lights_toon_fragment:pR,lights_toon_pars_fragment:mR,lights_phong_fragment:gR,lights_phong_pars_fragment:yR,lights_physical_fragment:_R,lights_physical_pars_fragment:xR,lights_fragment_begin:vR,lights_fragment_maps:bR,lights_fragment_end:SR,lightprobes_pars_fragment:MR,logdepthbuf_fragment:ER,logdepthbuf_pars_fragment:wR,logdepthbuf_pars_vertex:AR,logdepthbuf_vertex:TR,map_fragment:RR,map_pars_fragment:IR,map_particle_fragment:CR,map_particle_pars_fragment:NR,metalnessmap_fragment:PR,metalnessmap_pars_fragment:LR,morphinstance_vertex:DR,morphcolor_vertex:UR,morphnormal_vertex:OR,morphtarget_pars_vertex:FR,morphtarget_vertex:BR,normal_fragment_begin:kR,normal_fragment_maps:VR,normal_pars_fragment:GR,normal_pars_vertex:zR,normal_vertex:HR,normalmap_pars_fragment:WR,clearcoat_normal_fragment_begin:XR,clearcoat_normal_fragment_maps:YR,clearcoat_pars_fragment:ZR,iridescence_pars_fragment:KR,opaque_fragment:$R,packing:qR,premultiplied_alpha_fragment:JR,project_vertex:jR,dithering_fragment:QR,dithering_pars_fragment:eI,roughnessmap_fragment:tI,roughnessmap_pars_fragment:nI,shadowmap_pars_fragment:iI,shadowmap_pars_vertex:rI,shadowmap_vertex:sI,shadowmask_pars_fragment:oI,skinbase_vertex:aI,skinning_pars_vertex:lI,skinning_vertex:cI,skinnormal_vertex:uI,specularmap_fragment:hI,specularmap_pars_fragment:fI,tonemapping_fragment:dI,tonemapping_pars_fragment:pI,transmission_fragment:mI,transmission_pars_fragment:gI,uv_pars_fragment:yI,uv_pars_vertex:_I,uv_vertex:xI,worldpos_vertex:vI,background_vert:bI,background_frag:SI,backgroundCube_vert:MI,backgroundCube_frag:EI,cube_vert:wI,cube_frag:AI,depth_vert:TI,depth_frag:RI,distance_vert:II,distance_frag:CI,equirect_vert:NI,equirect_frag:PI,linedashed_vert:LI,linedashed_frag:DI,meshbasic_vert:UI,meshbasic_frag:OI,meshlambert_vert:FI,meshlambert_frag:BI,meshmatcap_vert:kI,meshmatcap_frag:VI,meshnormal_vert:GI,meshnormal_frag:zI,meshphong_vert:HI,meshphong_frag:WI,meshphysical_vert:XI,meshphysical_frag:YI,meshtoon_vert:ZI,meshtoon_frag:KI,points_vert:$I,points_frag:qI,shadow_vert:JI,shadow_frag:jI,sprite_vert:QI,sprite_frag:eC},Le={common:{diffuse:{value:new ft(16777215)},opacity:{value:1},map:{value:null},mapTransform:{value:new rt},alphaMap:{value:null},alphaMapTransform:{value:new rt},alphaTest:{value:0}},specularmap:{specularMap:{value:null},specularMapTransform:{value:new rt}},envmap:{envMap:{value:null},envMapRotation:{value:new rt},reflectivity:{value:1},ior:{value:1.5},refractionRatio:{value:.98},dfgLUT:{value:null}},aomap:{aoMap:{value:null},aoMapIntensity:{value:1},aoMapTransform:{value:new rt}},lightmap:{lightMap:{value:null},lightMapIntensity:{value:1},lightMapTransform:{value:new rt}},bumpmap:{bumpMap:{value:null},bumpMapTransform:{value:new rt},bumpScale:{value:1}},normalmap:{normalMap:{value:null},normalMapTransform:{value:new rt},normalScale:{value:new it(1,1)}},displacementmap:{displacementMap:{value:null},displacementMapTransform:{value:new rt},displacementScale:{value:1},displacementBias:{value:0}},emissivemap:{emissiveMap:{value:null},emissiveMapTransform:{value:new rt}},metalnessmap:{metalnessMap:{value:null},metalnessMapTransform:{value:new rt}},roughnessmap:{roughnessMap:{value:null},roughnessMapTransform:{value:new rt}},gradientmap:{gradientMap:{value:null}},fog:{fogDensity:{value:25e-5},fogNear:{value:1},fogFar:{value:2e3},fogColor:{value:new ft(16777215)}},lights:{ambientLightColor:{value:[]},lightProbe:{value:[]},sunLights:{value:[],properties:{direction:{},color:{}}},sunLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{}}},sunShadowMatrix:{value:[]},sunShadowCascade:{value:[]},directionalLights:{value:[],properties:{direction:{},color:{}}},directionalLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{}}},directionalShadowMatrix:{value:[]},spotLights:{value:[],properties:{color:{},position:{},direction:{},distance:{},coneCos:{},penumbraCos:{},decay:{}}},spotLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{}}},spotLightMap:{value:[]},spotLightMatrix:{value:[]},pointLights:{value:[],properties:{color:{},position:{},decay:{},distance:{}}},pointLightShadows:{value:[],properties:{shadowIntensity:1,shadowBias:{},shadowNormalBias:{},shadowRadius:{},shadowMapSize:{},shadowCameraNear:{},shadowCameraFar:{}}},pointShadowMatrix:{value:[]},hemisphereLights:{value:[],properties:{direction:{},skyColor:{},groundColor:{}}},rectAreaLights:{value:[],properties:{color:{},position:{},width:{},height:{}}},ltc_1:{value:null},ltc_2:{value:null},probesSH:{value:[]},probesMin:{value:[]},probesMax:{value:[]},probesResolution:{value:[]}},points:{diffuse:{value:new ft(16777215)},opacity:{value:1},size:{value:1},scale:{value:1},map:{value:null},alphaMap:{value:null},alphaMapTransform:{value:new rt},alphaTest:{value:0},uvTransform:{value:new rt}},sprite:{diffuse:{value:new ft(16777215)},opacity:{value:1},center:{value:new it(.5,.5)},rotation:{value:0},map:{value:null},mapTransform:{value:new rt},alphaMap:{value:null},alphaMapTransform:{value:new rt},alphaTest:{value:0}}},Mr={basic:{uniforms:Jn([Le.common,Le.specularmap,Le.envmap,Le.aomap,Le.lightmap,Le.fog]),vertexShader:dt.meshbasic_vert,fragmentShader:dt.meshbasic_frag},lambert:{uniforms:Jn([Le.common,Le.specularmap,Le.envmap,Le.aomap,Le.lightmap,Le.emissivemap,Le.bumpmap,Le.normalmap,Le.displacementmap,Le.fog,Le.lights,{emissive:{value:new ft(0)},envMapIntensity:{value:1}}]),vertexShader:dt.meshlambert_vert,fragmentShader:dt.meshlambert_frag},phong:{uniforms:Jn([Le.common,Le.specularmap,Le.envmap,Le.aomap,Le.lightmap,Le.emissivemap,Le.bumpmap,Le.normalmap,Le.displacementmap,Le.fog,Le.lights,{emissive:{value:new ft(0)},specular:{value:new ft(1118481)},shininess:{value:30},envMapIntensity:{value:1}}]),vertexShader:dt.meshphong_vert,fragmentShader:dt.meshphong_frag},standard:{uniforms:Jn([Le.common,Le.envmap,Le.aomap,Le.lightmap,Le.emissivemap,Le.bumpmap,Le.normalmap,Le.displacementmap,Le.roughnessmap,Le.metalnessmap,Le.fog,Le.lights,{emissive:{value:new ft(0)},roughness:{value:1},metalness:{value:0},envMapIntensity:{value:1}}]),vertexShader:dt.meshphysical_vert,fragmentShader:dt.meshphysical_frag},toon:{uniforms:Jn([Le.common,Le.aomap,Le.lightmap,Le.emissivemap,Le.bumpmap,Le.normalmap,Le.displacementmap,Le.gradientmap,Le.fog,Le.lights,{emissive:{value:new ft(0)}}]),vertexShader:dt.meshtoon_vert,fragmentShader:dt.meshtoon_frag},matcap:{uniforms:Jn([Le.common,Le.bumpmap,Le.normalmap,Le.displacementmap,Le.fog,{matcap:{value:null}}]),vertexShader:dt.meshmatcap_vert,fragmentShader:dt.meshmatcap_frag},points:{uniforms:Jn([Le.points,Le.fog]),vertexShader:dt.points_vert,fragmentShader:dt.points_frag},dashed:{uniforms:Jn([Le.common,Le.fog,{scale:{value:1},dashSize:{value:1},totalSize:{value:2}}]),vertexShader:dt.linedashed_vert,fragmentShader:dt.linedashed_frag},depth:{uniforms:Jn([Le.common,Le.displacementmap]),vertexShader:dt.depth_vert,fragmentShader:dt.depth_frag},normal:{uniforms:Jn([Le.common,Le.bumpmap,Le.normalmap,Le.displacementmap,{opacity:{value:1}}]),vertexShader:dt.meshnormal_vert,fragmentShader:dt.meshnormal_frag},sprite:{uniforms:Jn([Le.sprite,Le.fog]),vertexShader:dt.sprite_vert,fragmentShader:dt.sprite_frag},background:{uniforms:{uvTransform:{value:new rt},t2D:{value:null},backgroundIntensity:{value:1}},vertexShader:dt.background_vert,fragmentShader:dt.background_frag},backgroundCube:{uniforms:{envMap:{value:null},backgroundBlurriness:{value:0},backgroundIntensity:{value:1},backgroundRotation:{value:new rt}},vertexShader:dt.backgroundCube_vert,fragmentShader:dt.backgroundCube_frag},cube:{uniforms:{tCube:{value:null},tFlip:{value:-1},opacity:{value:1}},vertexShader:dt.cube_vert,fragmentShader:dt.cube_frag},equirect:{uniforms:{tEquirect:{value:null}},vertexShader:dt.equirect_vert,fragmentShader:dt.equirect_frag},distance:{uniforms:Jn([Le.common,Le.displacementmap,{referencePosition:{value:new Y},nearDistance:{value:1},farDistance:{value:1e3}}]),vertexShader:dt.distance_vert,fragmentShader:dt.distance_frag},shadow:{uniforms:Jn([Le.lights,Le.fog,{color:{value:new ft(0)},opacity:{value:1}}]),vertexShader:dt.shadow_vert,fragmentShader:dt.shadow_frag}};Mr.physical={uniforms:Jn([Mr.standard.uniforms,{clearcoat:{value:0},clearcoatMap:{value:null},clearcoatMapTransform:{value:new rt},clearcoatNormalMap:{value:null},clearcoatNormalMapTransform:{value:new rt},clearcoatNormalScale:{value:new it(1,1)},clearcoatRoughness:{value:0},clearcoatRoughnessMap:{value:null},clearcoatRoughnessMapTransform:{value:new rt},diffuseRoughness:{value:0},diffuseRoughnessMap:{value:null},diffuseRoughnessMapTransform:{value:new rt},dispersion:{value:0},retroreflectivity:{value:0},iridescence:{value:0},iridescenceMap:{value:null},iridescenceMapTransform:{value:new rt},iridescenceIOR:{value:1.3},iridescenceThicknessMinimum:{value:100},iridescenceThicknessMaximum:{value:400},iridescenceThicknessMap:{value:null},iridescenceThicknessMapTransform:{value:new rt},sheen:{value:0},sheenColor:{value:new ft(0)},sheenColorMap:{value:null},sheenColorMapTransform:{value:new rt},sheenRoughness:{value:1},sheenRoughnessMap:{value:null},sheenRoughnessMapTransform:{value:new rt},transmission:{value:0},transmissionMap:{value:null},transmissionMapTransform:{value:new rt},transmissionSamplerSize:{value:new it},transmissionSamplerMap:{value:null},thickness:{value:0},thicknessMap:{value:null},thicknessMapTransform:{value:new rt},attenuationDistance:{value:0},attenuationColor:{value:new ft(0)},specularColor:{value:new ft(1,1,1)},specularColorMap:{value:null},specularColorMapTransform:{value:new rt},specularIntensity:{value:1},specularIntensityMap:{value:null},specularIntensityMapTransform:{value:new rt},anisotropyVector:{value:new it},anisotropyMap:{value:null},anisotropyMapTransform:{value:new rt}}]),vertexShader:dt.meshphysical_vert,fragmentShader:dt.meshphysical_frag};var of={r:0,b:0,g:0},tC=new Ht,Xb=new rt;Xb.set(-1,0,0,0,1,0,0,0,1);function nC(n,e,t,i,r,s){let o=new ft(0),a=r===!0?0:1,l,c,u=null,h=0,f=null;function d(v){let T=v.isScene===!0?v.background:null;if(T&&T.isTexture){let M=v.backgroundBlurriness>0;T=e.get(T,M)}return T}function p(v){let T=!1,M=d(v);M===null?m(o,a):M&&M.isColor&&(m(M,1),T=!0);let R=n.xr.getEnvironmentBlendMode();R==="additive"?t.buffers.color.setClear(0,0,0,1,s):R==="alpha-blend"&&t.buffers.color.setClear(0,0,0,0,s),(n.autoClear||T)&&(t.buffers.depth.setTest(!0),t.buffers.depth.setMask(!0),t.buffers.color.setMask(!0),n.clear(n.autoClearColor,n.autoClearDepth,n.autoClearStencil))}function x(v,T){let M=d(T);M&&M.isCubeTexture?(c===void 0&&(c=new Ti(new na(1,1,1),new vr({name:"BackgroundCubeMaterial",uniforms:qs(Mr.backgroundCube.uniforms),vertexShader:Mr.backgroundCube.vertexShader,fragmentShader:Mr.backgroundCube.fragmentShader,side:ui,depthTest:!1,depthWrite:!1,fog:!1,allowOverride:!1})),c.geometry.deleteAttribute("normal"),c.geometry.deleteAttribute("uv"),c.onBeforeRender=function(R,w,y){this.matrixWorld.copyPosition(y.matrixWorld)},Object.defineProperty(c.material,"envMap",{get:function(){return this.uniforms.envMap.value}}),i.update(c)),c.material.uniforms.envMap.value=M,c.material.uniforms.backgroundBlurriness.value=T.backgroundBlurriness,c.material.uniforms.backgroundIntensity.value=T.backgroundIntensity,c.material.uniforms.backgroundRotation.value.setFromMatrix4(tC.makeRotationFromEuler(T.backgroundRotation)).transpose(),M.isRenderTargetTexture===!1&&c.material.uniforms.backgroundRotation.value.premultiply(Xb),c.material.toneMapped=vt.getTransfer(M.colorSpace)!==Nt,(u!==M||h!==M.version||f!==n.toneMapping)&&(c.material.needsUpdate=!0,u=M,h=M.version,f=n.toneMapping),c.layers.enableAll(),v.unshift(c,c.geometry,c.material,0,0,null)):M&&M.isTexture&&(l===void 0&&(l=new Ti(new Al(2,2),new vr({name:"BackgroundMaterial",uniforms:qs(Mr.background.uniforms),vertexShader:Mr.background.vertexShader,fragmentShader:Mr.background.fragmentShader,side:vs,depthTest:!1,depthWrite:!1,fog:!1,allowOverride:!1})),l.geometry.deleteAttribute("normal"),Object.defineProperty(l.material,"map",{get:function(){return this.uniforms.t2D.value}}),i.update(l)),l.material.uniforms.t2D.value=M,l.material.uniforms.backgroundIntensity.value=T.backgroundIntensity,l.material.toneMapped=vt.getTransfer(M.colorSpace)!==Nt,M.matrixAutoUpdate===!0&&M.updateMatrix(),l.material.uniforms.uvTransform.value.copy(M.matrix),(u!==M||h!==M.version||f!==n.toneMapping)&&(l.material.needsUpdate=!0,u=M,h=M.version,f=n.toneMapping),l.layers.enableAll(),v.unshift(l,l.geometry,l.material,0,0,null))}function m(v,T){v.getRGB(of,Lm(n)),t.buffers.color.setClear(of.r,of.g,of.b,T,s)}function g(){c!==void 0&&(c.geometry.dispose(),c.material.dispose(),c=void 0),l!==void 0&&(l.geometry.dispose(),l.material.dispose(),l=void 0)}return{getClearColor:function(){return o},setClearColor:function(v,T=1){o.set(v),a=T,m(o,a)},getClearAlpha:function(){return a},setClearAlpha:function(v){a=v,m(o,a)},render:p,addToRenderList:x,dispose:g}}function iC(n,e){let t=n.getParameter(n.MAX_VERTEX_ATTRIBS),i={},r=f(null),s=r,o=!1;function a(L,H,z,N,F){let Z=!1,V=h(L,N,z,H);s!==V&&(s=V,c(s.object)),Z=d(L,N,z,F),Z&&p(L,N,z,F),F!==null&&e.update(F,n.ELEMENT_ARRAY_BUFFER),(Z||o)&&(o=!1,M(L,H,z,N),F!==null&&n.bindBuffer(n.ELEMENT_ARRAY_BUFFER,e.get(F).buffer))}function l(){return n.createVertexArray()}function c(L){return n.bindVertexArray(L)}function u(L){return n.deleteVertexArray(L)}function h(L,H,z,N){let F=N.wireframe===!0,Z=i[H.id];Z===void 0&&(Z={},i[H.id]=Z);let V=L.isInstancedMesh===!0?L.id:0,le=Z[V];le===void 0&&(le={},Z[V]=le);let q=le[z.id];q===void 0&&(q={},le[z.id]=q);let Q=q[F];return Q===void 0&&(Q=f(l()),q[F]=Q),Q}function f(L){let H=[],z=[],N=[];for(let F=0;F<t;F++)H[F]=0,z[F]=0,N[F]=0;return{geometry:null,program:null,wireframe:!1,newAttributes:H,enabledAttributes:z,attributeDivisors:N,object:L,attributes:{},index:null}}function d(L,H,z,N){let F=s.attributes,Z=H.attributes,V=0,le=z.getAttributes();for(let q in le)if(le[q].location>=0){let ie=F[q],fe=Z[q];if(fe===void 0&&(q==="instanceMatrix"&&L.instanceMatrix&&(fe=L.instanceMatrix),q==="instanceColor"&&L.instanceColor&&(fe=L.instanceColor)),ie===void 0||ie.attribute!==fe||fe&&ie.data!==fe.data)return!0;V++}return s.attributesNum!==V||s.index!==N}function p(L,H,z,N){let F={},Z=H.attributes,V=0,le=z.getAttributes();for(let q in le)if(le[q].location>=0){let ie=Z[q];ie===void 0&&(q==="instanceMatrix"&&L.instanceMatrix&&(ie=L.instanceMatrix),q==="instanceColor"&&L.instanceColor&&(ie=L.instanceColor));let fe={};fe.attribute=ie,ie&&ie.data&&(fe.data=ie.data),F[q]=fe,V++}s.attributes=F,s.attributesNum=V,s.index=N}function x(){let L=s.newAttributes;for(let H=0,z=L.length;H<z;H++)L[H]=0}function m(L){g(L,0)}function g(L,H){let z=s.newAttributes,N=s.enabledAttributes,F=s.attributeDivisors;z[L]=1,N[L]===0&&(n.enableVertexAttribArray(L),N[L]=1),F[L]!==H&&(n.vertexAttribDivisor(L,H),F[L]=H)}function v(){let L=s.newAttributes,H=s.enabledAttributes;for(let z=0,N=H.length;z<N;z++)H[z]!==L[z]&&(n.disableVertexAttribArray(z),H[z]=0)}function T(L,H,z,N,F,Z,V){V===!0?n.vertexAttribIPointer(L,H,z,F,Z):n.vertexAttribPointer(L,H,z,N,F,Z)}function M(L,H,z,N){x();let F=N.attributes,Z=z.getAttributes(),V=H.defaultAttributeValues;for(let le in Z){let q=Z[le];if(q.location>=0){let Q=F[le];if(Q===void 0&&(le==="instanceMatrix"&&L.instanceMatrix&&(Q=L.instanceMatrix),le==="instanceColor"&&L.instanceColor&&(Q=L.instanceColor)),Q!==void 0){let ie=Q.normalized,fe=Q.itemSize,he=e.get(Q);if(he===void 0)continue;let ee=he.buffer,ge=he.type,ye=he.bytesPerElement,xe=ge===n.INT||ge===n.UNSIGNED_INT||Q.gpuType===Sh;if(Q.isInterleavedBufferAttribute){let _e=Q.data,ze=_e.isInterleavedBuffer===!0?_e.stride:_e.itemSize,$e=Q.offset;if(_e.isInstancedInterleavedBuffer||_e.isInstancedBufferAttribute){for(let Fe=0;Fe<q.locationSize;Fe++)g(q.location+Fe,_e.meshPerAttribute);L.isInstancedMesh!==!0&&N._maxInstanceCount===void 0&&(N._maxInstanceCount=_e.meshPerAttribute*_e.count)}else for(let Fe=0;Fe<q.locationSize;Fe++)m(q.location+Fe);n.bindBuffer(n.ARRAY_BUFFER,ee);for(let Fe=0;Fe<q.locationSize;Fe++)T(q.location+Fe,fe/q.locationSize,ge,ie,ze*ye,($e+fe/q.locationSize*Fe)*ye,xe)}else{if(Q.isInstancedBufferAttribute){for(let _e=0;_e<q.locationSize;_e++)g(q.location+_e,Q.meshPerAttribute);L.isInstancedMesh!==!0&&N._maxInstanceCount===void 0&&(N._maxInstanceCount=Q.meshPerAttribute*Q.count)}else for(let _e=0;_e<q.locationSize;_e++)m(q.location+_e);n.bindBuffer(n.ARRAY_BUFFER,ee);for(let _e=0;_e<q.locationSize;_e++)T(q.location+_e,fe/q.locationSize,ge,ie,fe*ye,fe/q.locationSize*_e*ye,xe)}}else if(V!==void 0){let ie=V[le];if(ie!==void 0)switch(ie.length){case 2:n.vertexAttrib2fv(q.location,ie);break;case 3:n.vertexAttrib3fv(q.location,ie);break;case 4:n.vertexAttrib4fv(q.location,ie);break;default:n.vertexAttrib1fv(q.location,ie)}}}}v()}function R(){k();for(let L in i){let H=i[L];for(let z in H){let N=H[z];for(let F in N){let Z=N[F];for(let V in Z)u(Z[V].object),delete Z[V];delete N[F]}}delete i[L]}}function w(L){if(i[L.id]===void 0)return;let H=i[L.id];for(let z in H){let N=H[z];for(let F in N){let Z=N[F];for(let V in Z)u(Z[V].object),delete Z[V];delete N[F]}}delete i[L.id]}function y(L){for(let H in i){let z=i[H];for(let N in z){let F=z[N];if(F[L.id]===void 0)continue;let Z=F[L.id];for(let V in Z)u(Z[V].object),delete Z[V];delete F[L.id]}}}function A(L){for(let H in i){let z=i[H],N=L.isInstancedMesh===!0?L.id:0,F=z[N];if(F!==void 0){for(let Z in F){let V=F[Z];for(let le in V)u(V[le].object),delete V[le];delete F[Z]}delete z[N],Object.keys(z).length===0&&delete i[H]}}}function k(){D(),o=!0,s!==r&&(s=r,c(s.object))}function D(){r.geometry=null,r.program=null,r.wireframe=!1}return{setup:a,reset:k,resetDefaultState:D,dispose:R,releaseStatesOfGeometry:w,releaseStatesOfObject:A,releaseStatesOfProgram:y,initAttributes:x,enableAttribute:m,disableUnusedAttributes:v}}function rC(n,e,t){let i;function r(l){i=l}function s(l,c){n.drawArrays(i,l,c),t.update(c,i,1)}function o(l,c,u){u!==0&&(n.drawArraysInstanced(i,l,c,u),t.update(c,i,u))}function a(l,c,u){if(u===0)return;e.get("WEBGL_multi_draw").multiDrawArraysWEBGL(i,l,0,c,0,u);let f=0;for(let d=0;d<u;d++)f+=c[d];t.update(f,i,1)}this.setMode=r,this.render=s,this.renderInstances=o,this.renderMultiDraw=a}function sC(n,e,t,i){let r;function s(){if(r!==void 0)return r;if(e.has("EXT_texture_filter_anisotropic")===!0){let y=e.get("EXT_texture_filter_anisotropic");r=n.getParameter(y.MAX_TEXTURE_MAX_ANISOTROPY_EXT)}else r=0;return r}function o(y){return!(y!==nr&&i.convert(y)!==n.getParameter(n.IMPLEMENTATION_COLOR_READ_FORMAT))}function a(y){let A=y===tr&&(e.has("EXT_color_buffer_half_float")||e.has("EXT_color_buffer_float"));return!(y!==di&&y!==er&&!A&&i.convert(y)!==n.getParameter(n.IMPLEMENTATION_COLOR_READ_TYPE))}function l(y){if(y==="highp"){if(n.getShaderPrecisionFormat(n.VERTEX_SHADER,n.HIGH_FLOAT).precision>0&&n.getShaderPrecisionFormat(n.FRAGMENT_SHADER,n.HIGH_FLOAT).precision>0)return"highp";y="mediump"}return y==="mediump"&&n.getShaderPrecisionFormat(n.VERTEX_SHADER,n.MEDIUM_FLOAT).precision>0&&n.getShaderPrecisionFormat(n.FRAGMENT_SHADER,n.MEDIUM_FLOAT).precision>0?"mediump":"lowp"}let c=t.precision!==void 0?t.precision:"highp",u=l(c);u!==c&&(Ke("WebGLRenderer:",c,"not supported, using",u,"instead."),c=u);let h=t.reversedDepthBuffer===!0&&e.has("EXT_clip_control"),f=t.logarithmicDepthBuffer===!0&&h===!1;t.reversedDepthBuffer===!0&&h===!1&&Ke("WebGLRenderer: Unable to use reversed depth buffer due to missing EXT_clip_control extension. Fallback to default depth buffer."),t.logarithmicDepthBuffer===!0&&h===!0&&Ke("WebGLRenderer: Logarithmic depth buffer is ignored when reversed depth buffer is enabled.");let d=n.getParameter(n.MAX_TEXTURE_IMAGE_UNITS),p=n.getParameter(n.MAX_VERTEX_TEXTURE_IMAGE_UNITS),x=n.getParameter(n.MAX_TEXTURE_SIZE),m=n.getParameter(n.MAX_CUBE_MAP_TEXTURE_SIZE),g=n.getParameter(n.MAX_VERTEX_ATTRIBS),v=n.getParameter(n.MAX_VERTEX_UNIFORM_VECTORS),T=n.getParameter(n.MAX_VARYING_VECTORS),M=n.getParameter(n.MAX_FRAGMENT_UNIFORM_VECTORS),R=n.getParameter(n.MAX_SAMPLES),w=n.getParameter(n.SAMPLES);return{isWebGL2:!0,getMaxAnisotropy:s,getMaxPrecision:l,textureFormatReadable:o,textureTypeReadable:a,precision:c,logarithmicDepthBuffer:f,reversedDepthBuffer:h,maxTextures:d,maxVertexTextures:p,maxTextureSize:x,maxCubemapSize:m,maxAttributes:g,maxVertexUniforms:v,maxVaryings:T,maxFragmentUniforms:M,maxSamples:R,samples:w}}function oC(n){let e=this,t=null,i=0,r=!1,s=!1,o=new oi,a=new rt,l={value:null,needsUpdate:!1};this.uniform=l,this.numPlanes=0,this.numIntersection=0,this.init=function(h,f){let d=h.length!==0||f||i!==0||r;return r=f,i=h.length,d},this.beginShadows=function(){s=!0,u(null)},this.endShadows=function(){s=!1},this.setGlobalState=function(h,f){t=u(h,f,0)},this.setState=function(h,f,d){let p=h.clippingPlanes,x=h.clipIntersection,m=h.clipShadows,g=n.get(h);if(!r||p===null||p.length===0||s&&!m)s?u(null):c();else{let v=s?0:i,T=v*4,M=g.clippingState||null;l.value=M,M=u(p,f,T,d);for(let R=0;R!==T;++R)M[R]=t[R];g.clippingState=M,this.numIntersection=x?this.numPlanes:0,this.numPlanes+=v}};function c(){l.value!==t&&(l.value=t,l.needsUpdate=i>0),e.numPlanes=i,e.numIntersection=0}function u(h,f,d,p){let x=h!==null?h.length:0,m=null;if(x!==0){if(m=l.value,p!==!0||m===null){let g=d+x*4,v=f.matrixWorldInverse;a.getNormalMatrix(v),(m===null||m.length<g)&&(m=new Float32Array(g));for(let T=0,M=d;T!==x;++T,M+=4)o.copy(h[T]).applyMatrix4(v,a),o.normal.toArray(m,M),m[M+3]=o.constant}l.value=m,l.needsUpdate=!0}return e.numPlanes=x,e.numIntersection=0,m}}var Wl=class extends Ai{constructor(e=1,t={}){super(e,e,t),this.isWebGLCubeRenderTarget=!0;let i={width:e,height:e,depth:1},r=[i,i,i,i,i,i];this.texture=new Ml(r),this._setTextureOptions(t),this.texture.isRenderTargetTexture=!0}fromEquirectangularTexture(e,t){this.texture.type=t.type,this.texture.colorSpace=t.colorSpace,this.texture.generateMipmaps=t.generateMipmaps,this.texture.minFilter=t.minFilter,this.texture.magFilter=t.magFilter;let i={uniforms:{tEquirect:{value:null}},vertexShader:`

				varying vec3 vWorldDirection;

				vec3 transformDirection( in vec3 dir, in mat4 matrix ) {

					return normalize( ( matrix * vec4( dir, 0.0 ) ).xyz );

				}

				void main() {

					vWorldDirection = transformDirection( position, modelMatrix );

					#include <begin_vertex>
					#include <project_vertex>

				}
			`,fragmentShader:`

				uniform sampler2D tEquirect;

				varying vec3 vWorldDirection;

				#include <common>

				void main() {

					vec3 direction = normalize( vWorldDirection );

					vec2 sampleUV = equirectUv( direction );

					gl_FragColor = texture2D( tEquirect, sampleUV );

				}
			`},r=new na(5,5,5),s=new vr({name:"CubemapFromEquirect",uniforms:qs(i.uniforms),vertexShader:i.vertexShader,fragmentShader:i.fragmentShader,side:ui,blending:Ys});s.uniforms.tEquirect.value=t;let o=new Ti(r,s),a=t.minFilter;return t.minFilter===Xr&&(t.minFilter=li),new sa(1,10,this).update(e,o),t.minFilter=a,o.geometry.dispose(),o.material.dispose(),this}clear(e,t=!0,i=!0,r=!0){let s=e.getRenderTarget();for(let o=0;o<6;o++)e.setRenderTarget(this,o),e.clear(t,i,r);e.setRenderTarget(s)}},Mb=256,aC=3,lC=20,Yb=256,Zb=16,cC=3,uC=new Y,hC=new ft,lf=class n{constructor(e){this._renderer=e,this._cubeSize=0,this._sourceTarget=null,this._cubeCamera=new sa(1,10,null),this._boxMesh=new Ti(new na(5,5,5),null),this._cubemapMaterial=null,this._equirectMaterial=null,this._blurMaterial=null,this._ggxMaterial=null,this._integrationMaterial=null}fromScene(e,t=0,i=.1,r=100,s={}){let{size:o=256,position:a=uC}=s,l=this._renderer;this._setSize(o);let c=this._allocateTarget(),u=this._getSourceTarget(!0);t>0&&(u.texture.mipmapsAutoUpdate=!1);let h=l.autoClear,f=l.autoClearColor,d=l.autoClearDepth,p=l.autoClearStencil,x=e.background;l.autoClear=!0,l.autoClearColor=!0,l.autoClearDepth=!0,l.autoClearStencil=!0,x===null&&(e.background=l.getClearColor(hC));let m=new sa(i,r,u);return m.position.copy(a),m.update(l,e),l.autoClear=h,l.autoClearColor=f,l.autoClearDepth=d,l.autoClearStencil=p,e.background=x,t>0&&(u.texture.mipmapsAutoUpdate=!0,this._blur(c,t)),this._applyPMREM(c),c}fromEquirectangular(e,t=null){return this._fromTexture(e,t)}fromCubemap(e,t=null){return this._fromTexture(e,t)}compileCubemapShader(){this._cubemapMaterial===null&&(this._cubemapMaterial=Ab(),this._compileMaterial(this._cubemapMaterial))}compileEquirectangularShader(){this._equirectMaterial===null&&(this._equirectMaterial=wb(),this._compileMaterial(this._equirectMaterial))}dispose(){this._sourceTarget!==null&&this._sourceTarget.dispose(),this._cubemapMaterial!==null&&this._cubemapMaterial.dispose(),this._equirectMaterial!==null&&this._equirectMaterial.dispose(),this._blurMaterial!==null&&this._blurMaterial.dispose(),this._ggxMaterial!==null&&this._ggxMaterial.dispose(),this._integrationMaterial!==null&&this._integrationMaterial.dispose(),this._boxMesh.geometry.dispose()}static lodToRoughness(e,t){return t>0?1-Math.sqrt(1-e/t):0}_setSize(e){this._cubeSize=Math.max(Mb,Cm(e))}_fromTexture(e,t){e.mapping===Ks||e.mapping===ca?this._setSize(e.image.length===0?Mb:e.image[0].width||e.image[0].image.width):this._setSize(e.image.width/4);let i=t||this._allocateTarget();return this._textureToCubemap(e),this._applyPMREM(i),i}_allocateTarget(){let e=this._cubeSize,t=Eb(e,!1,!1),i=Math.log2(e)-aC;for(let r=0;r<=i;r++)t.texture.mipmaps.push({width:e>>r,height:e>>r});return t.texture.name="PMREM",t.texture.isPMREMTexture=!0,t}_getSourceTarget(e=!1){let t=this._cubeSize,i=this._sourceTarget;return(i===null||i.width!==t||e&&i.depthBuffer===!1)&&(i!==null&&i.dispose(),this._sourceTarget=Eb(t,!0,e)),this._sourceTarget}_compileMaterial(e){this._boxMesh.material=e,this._renderer.compile(this._boxMesh,this._cubeCamera.children[0])}_renderCube(e,t,i){let r=this._boxMesh,s=this._cubeCamera;r.material=i,s.renderTarget=e,s.activeMipmapLevel=t;let o=e.width>>t;e.viewport.set(0,0,o,o),s.update(this._renderer,r),e.viewport.set(0,0,e.width,e.height)}_textureToCubemap(e){let t;e.mapping===Ks||e.mapping===ca?(this._cubemapMaterial===null&&(this._cubemapMaterial=Ab()),t=this._cubemapMaterial,t.uniforms.flipEnvMap.value=e.isRenderTargetTexture===!1?-1:1):(this._equirectMaterial===null&&(this._equirectMaterial=wb()),t=this._equirectMaterial),t.uniforms.envMap.value=e,this._renderCube(this._getSourceTarget(),0,t)}_applyPMREM(e){this._ggxMaterial===null&&(this._ggxMaterial=fC(),this._integrationMaterial=dC());let t=this._cubeSize,i=e.texture.mipmaps.length-1,r=this._ggxMaterial.uniforms;r.envMap.value=this._sourceTarget.texture;let s=this._integrationMaterial.uniforms;s.envMap.value=this._sourceTarget.texture,s.sourceLod.value=Math.log2(t/Zb);for(let o=0;o<=i;o++){let a=n.lodToRoughness(o,i);if(o>i-cC)s.roughness.value=a,this._renderCube(e,o,this._integrationMaterial);else{let l=a>0?Math.log2(t)+.5*Math.log2(6/(Yb*Math.pow(a,4)))+.5:0;r.roughness.value=a,r.lodBias.value=l,this._renderCube(e,o,this._ggxMaterial)}}}_blur(e,t){this._blurMaterial===null&&(this._blurMaterial=pC());let i=this._blurMaterial,r=i.uniforms,s=this._sourceTarget;r.sigma.value=Math.min(t,Math.PI)/Math.SQRT2,r.envMap.value=s.texture,this._renderCube(e,0,i),r.envMap.value=e.texture,this._renderCube(s,0,i)}};function Eb(n,e,t){return new Wl(n,{minFilter:Xr,generateMipmaps:e,type:tr,colorSpace:dl,depthBuffer:t})}function Xl(n,e,t){return new vr({name:n,uniforms:e,vertexShader:dt.cube_vert,fragmentShader:t,side:ui,blending:Ys,depthTest:!1,depthWrite:!1})}function fC(){return Xl("PMREMGGXConvolution",{envMap:{value:null},roughness:{value:0},lodBias:{value:0}},`

		#define GGX_SAMPLES ${Yb}u

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float roughness;
		uniform float lodBias;

		#include <common>

		// Van der Corput radical inverse
		float radicalInverse_VdC( uint bits ) {

			bits = ( bits << 16u ) | ( bits >> 16u );
			bits = ( ( bits & 0x55555555u ) << 1u ) | ( ( bits & 0xAAAAAAAAu ) >> 1u );
			bits = ( ( bits & 0x33333333u ) << 2u ) | ( ( bits & 0xCCCCCCCCu ) >> 2u );
			bits = ( ( bits & 0x0F0F0F0Fu ) << 4u ) | ( ( bits & 0xF0F0F0F0u ) >> 4u );
			bits = ( ( bits & 0x00FF00FFu ) << 8u ) | ( ( bits & 0xFF00FF00u ) >> 8u );
			return float( bits ) * 2.3283064365386963e-10; // / 0x100000000

		}

		// Hammersley sequence
		vec2 hammersley( uint i, uint N ) {

			return vec2( float( i ) / float( N ), radicalInverse_VdC( i ) );

		}

		void main() {

			vec3 N = normalize( vWorldDirection );

			// For very low roughness, just sample the environment directly
			if ( roughness < 0.001 ) {

				gl_FragColor = vec4( textureLod( envMap, N, 0.0 ).rgb, 1.0 );
				return;

			}

			float alpha = roughness * roughness;
			float alpha2 = alpha * alpha;

			// Tangent space basis for VNDF sampling
			vec3 up = abs( N.z ) < 0.999 ? vec3( 0.0, 0.0, 1.0 ) : vec3( 1.0, 0.0, 0.0 );
			vec3 tangent = normalize( cross( up, N ) );
			vec3 bitangent = cross( N, tangent );

			vec3 prefilteredColor = vec3( 0.0 );
			float totalWeight = 0.0;

			for ( uint i = 0u; i < GGX_SAMPLES; i ++ ) {

				vec2 Xi = hammersley( i, GGX_SAMPLES );

				// With V = N, sample the reflected direction directly.
				float invQ = 1.0 / ( 1.0 - Xi.x + alpha2 * Xi.x );
				float NdotL = ( 1.0 - Xi.x - alpha2 * Xi.x ) * invQ;

				if ( NdotL > 0.0 ) {

					float phi = 2.0 * PI * Xi.y;
					float sinTheta = 2.0 * alpha * sqrt( Xi.x * ( 1.0 - Xi.x ) ) * invQ;
					vec3 L = N * NdotL + ( tangent * cos( phi ) + bitangent * sin( phi ) ) * sinTheta;

					// Match the source mip to the sample's solid angle. The terms
					// independent of the sample are precomputed in lodBias.
					float d = alpha2 * invQ;
					float lod = max( log2( d ) + lodBias, 0.0 );

					// Weight by NdotL for the split-sum approximation
					prefilteredColor += textureLod( envMap, L, lod ).rgb * NdotL;
					totalWeight += NdotL;

				}

			}

			gl_FragColor = vec4( prefilteredColor / totalWeight, 1.0 );

		}
	`)}function dC(){return Xl("PMREMGGXIntegration",{envMap:{value:null},roughness:{value:0},sourceLod:{value:0},sourceSize:{value:Zb}},`

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float roughness;
		uniform float sourceLod;
		uniform int sourceSize;

		void main() {

			vec3 N = normalize( vWorldDirection );

			float alpha = roughness * roughness;
			float alpha2 = alpha * alpha;

			float texelSize = 2.0 / float( sourceSize );

			vec3 prefilteredColor = vec3( 0.0 );
			float totalWeight = 0.0;

			// Pair opposite texels: only the one in N's hemisphere contributes.
			for ( int face = 0; face < 3; face ++ ) {

				for ( int y = 0; y < sourceSize; y ++ ) {

					for ( int x = 0; x < sourceSize; x ++ ) {

						vec2 uv = ( vec2( x, y ) + 0.5 ) * texelSize - 1.0;
						vec3 texelDirection = face == 0 ? vec3( 1.0, uv ) : ( face == 1 ? vec3( uv.x, 1.0, uv.y ) : vec3( uv, 1.0 ) );

						float invDistance = inversesqrt( 1.0 + dot( uv, uv ) );
						float NdotL = dot( N, texelDirection );
						texelDirection *= NdotL < 0.0 ? - 1.0 : 1.0;
						NdotL = abs( NdotL ) * invDistance;

						// With V = N, NdotH squared is ( 1 + NdotL ) / 2. Common factors
						// in the GGX distribution and texel solid angle cancel when normalized.
						float d = 1.0 + alpha2 + ( alpha2 - 1.0 ) * NdotL;
						float weight = NdotL * invDistance * invDistance * invDistance / ( d * d );

						prefilteredColor += textureLod( envMap, texelDirection, sourceLod ).rgb * weight;
						totalWeight += weight;

					}

				}

			}

			gl_FragColor = vec4( prefilteredColor / totalWeight, 1.0 );

		}
	`)}function pC(){return Xl("PMREMSphericalGaussianBlur",{envMap:{value:null},sigma:{value:0}},`

		#define SAMPLES ${lC}
		#define GOLDEN_ANGLE 2.39996322973

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float sigma;

		#include <common>

		void main() {

			vec3 outputDirection = normalize( vWorldDirection );

			vec3 up = abs( outputDirection.z ) < 0.999 ? vec3( 0.0, 0.0, 1.0 ) : vec3( 1.0, 0.0, 0.0 );
			vec3 tangent = normalize( cross( up, outputDirection ) );
			vec3 bitangent = cross( outputDirection, tangent );

			// Truncate the kernel at three standard deviations or at the antipode.
			float thetaMax = min( 3.0 * sigma, PI );
			float truncation = 1.0 - exp( - 0.5 * thetaMax * thetaMax / ( sigma * sigma ) );

			vec3 accumColor = vec3( 0.0 );
			float accumWeight = 0.0;

			for ( int i = 0; i < SAMPLES; i ++ ) {

				// Stratified inverse-CDF sampling of the Gaussian, placed on a golden-angle spiral.
				float stratum = ( float( i ) + 0.5 ) / float( SAMPLES );
				float theta = sigma * sqrt( - 2.0 * log( 1.0 - stratum * truncation ) );
				float phi = float( i ) * GOLDEN_ANGLE;

				vec3 offset = cos( phi ) * tangent + sin( phi ) * bitangent;
				vec3 sampleDirection = cos( theta ) * outputDirection + sin( theta ) * offset;

				// Correct the planar sample density to solid angle.
				float weight = sin( theta ) / theta;

				accumColor += weight * textureLod( envMap, sampleDirection, 0.0 ).rgb;
				accumWeight += weight;

			}

			gl_FragColor = vec4( accumColor / accumWeight, 1.0 );

		}
	`)}function wb(){return Xl("PMREMEquirectangularToCubemap",{envMap:{value:null}},`

		varying vec3 vWorldDirection;

		uniform sampler2D envMap;

		#include <common>

		void main() {

			// Average four subpixel samples to preserve small, bright features.
			vec3 direction = normalize( vWorldDirection );
			vec3 dx = dFdx( direction ) * 0.25;
			vec3 dy = dFdy( direction ) * 0.25;

			vec3 color = textureLod( envMap, equirectUv( normalize( direction - dx - dy ) ), 0.0 ).rgb;
			color += textureLod( envMap, equirectUv( normalize( direction + dx - dy ) ), 0.0 ).rgb;
			color += textureLod( envMap, equirectUv( normalize( direction - dx + dy ) ), 0.0 ).rgb;
			color += textureLod( envMap, equirectUv( normalize( direction + dx + dy ) ), 0.0 ).rgb;
			gl_FragColor = vec4( color * 0.25, 1.0 );

		}
	`)}function Ab(){return Xl("PMREMCubemapToCubemap",{envMap:{value:null},flipEnvMap:{value:-1}},`

		varying vec3 vWorldDirection;

		uniform samplerCube envMap;
		uniform float flipEnvMap;

		void main() {

			gl_FragColor = vec4( textureCube( envMap, vec3( flipEnvMap * vWorldDirection.x, vWorldDirection.yz ) ).rgb, 1.0 );

		}
	`)}function mC(n){let e=new WeakMap,t=new WeakMap,i=null;function r(f,d=!1){return f==null?null:d?o(f):s(f)}function s(f){if(f&&f.isTexture){let d=f.mapping;if(d===xh||d===vh)if(e.has(f)){let p=e.get(f).texture;return a(p,f.mapping)}else{let p=f.image;if(p&&p.height>0){let x=new Wl(p.height);return x.fromEquirectangularTexture(n,f),e.set(f,x),f.addEventListener("dispose",c),a(x.texture,f.mapping)}else return null}}return f}function o(f){if(f&&f.isTexture&&f.isPMREMTexture!==!0){let d=f.mapping,p=d===xh||d===vh,x=d===Ks||d===ca;if(p||x){let m=t.get(f),g=m!==void 0?m.texture.pmremVersion:0;if(f.isRenderTargetTexture&&f.pmremVersion!==g)return i===null&&(i=new lf(n)),m=p?i.fromEquirectangular(f,m):i.fromCubemap(f,m),m.texture.pmremVersion=f.pmremVersion,t.set(f,m),m.texture;if(m!==void 0)return m.texture;{let v=f.image;return p&&v&&v.height>0||x&&v&&l(v)?(i===null&&(i=new lf(n)),m=p?i.fromEquirectangular(f):i.fromCubemap(f),m.texture.pmremVersion=f.pmremVersion,t.set(f,m),f.addEventListener("dispose",u),m.texture):null}}}return f}function a(f,d){return d===xh?f.mapping=Ks:d===vh&&(f.mapping=ca),f}function l(f){let d=0,p=6;for(let x=0;x<p;x++)f[x]!==void 0&&d++;return d===p}function c(f){let d=f.target;d.removeEventListener("dispose",c);let p=e.get(d);p!==void 0&&(e.delete(d),p.dispose())}function u(f){let d=f.target;d.removeEventListener("dispose",u);let p=t.get(d);p!==void 0&&(t.delete(d),p.dispose())}function h(){e=new WeakMap,t=new WeakMap,i!==null&&(i.dispose(),i=null)}return{get:r,dispose:h}}function gC(n){let e={};function t(i){if(e[i]!==void 0)return e[i];let r=n.getExtension(i);return e[i]=r,r}return{has:function(i){return t(i)!==null},init:function(){t("EXT_color_buffer_float"),t("WEBGL_clip_cull_distance"),t("OES_texture_float_linear"),t("EXT_color_buffer_half_float"),t("WEBGL_multisampled_render_to_texture"),t("WEBGL_render_shared_exponent")},get:function(i){let r=t(i);return r===null&&cl("WebGLRenderer: "+i+" extension not supported."),r}}}function yC(n,e,t,i){let r={},s=new WeakMap,o=new FinalizationRegistry(p=>delete r[p]);function a(p){l(p.target)}function l(p){p.index!==null&&e.remove(p.index);for(let m in p.attributes)e.remove(p.attributes[m]);p.removeEventListener("dispose",a),delete r[p.id],o.unregister(p);let x=s.get(p);x&&(e.remove(x),s.delete(p)),i.releaseStatesOfGeometry(p),p.isInstancedBufferGeometry===!0&&delete p._maxInstanceCount,t.memory.geometries--}function c(p,x){return r[x.id]!==void 0||(x.addEventListener("dispose",a),r[x.id]=new WeakRef(x),o.register(x,x.id,x),t.memory.geometries++),x}function u(p){let x=p.attributes;for(let m in x)e.update(x[m],n.ARRAY_BUFFER)}function h(p){let x=p.index,m=p.attributes.position,g=0;if(m===void 0)return;let v=x!==null?x.array.length:m.array.length/3-1,T=m.count>=65535?vl:xl,M=new T(Math.ceil(v/3)*6,1),R=M.array;if(x!==null){let y=x.array;g=x.version;for(let A=0,k=0;A<v;A+=3){let D=y[A+0],L=y[A+1],H=y[A+2];R[k++]=D,R[k++]=L,R[k++]=L,R[k++]=H,R[k++]=H,R[k++]=D}}else{g=m.version;for(let y=0,A=0;y<v;y+=3){let k=y+0,D=y+1,L=y+2;R[A++]=k,R[A++]=D,R[A++]=D,R[A++]=L,R[A++]=L,R[A++]=k}}M.version=g;let w=s.get(p);w&&e.remove(w),s.set(p,M)}function f(p){let x=s.get(p);if(x){let m=p.index;m!==null&&x.version<m.version&&h(p)}else h(p);return s.get(p)}function d(){for(let p in r){let x=r[p].deref();x!==void 0&&l(x)}}return{get:c,update:u,getWireframeAttribute:f,dispose:d}}function _C(n,e,t){let i;function r(h){i=h}let s,o;function a(h){s=h.type,o=h.bytesPerElement}function l(h,f){n.drawElements(i,f,s,h*o),t.update(f,i,1)}function c(h,f,d){d!==0&&(n.drawElementsInstanced(i,f,s,h*o,d),t.update(f,i,d))}function u(h,f,d){if(d===0)return;e.get("WEBGL_multi_draw").multiDrawElementsWEBGL(i,f,0,s,h,0,d);let x=0;for(let m=0;m<d;m++)x+=f[m];t.update(x,i,1)}this.setMode=r,this.setIndex=a,this.render=l,this.renderInstances=c,this.renderMultiDraw=u}function xC(n){let e={geometries:0,textures:0},t={frame:0,calls:0,triangles:0,points:0,lines:0};function i(s,o,a){switch(t.calls++,o){case n.TRIANGLES:t.triangles+=a*(s/3);break;case n.LINES:t.lines+=a*(s/2);break;case n.LINE_STRIP:t.lines+=a*(s-1);break;case n.LINE_LOOP:t.lines+=a*s;break;case n.POINTS:t.points+=a*s;break;default:nt("WebGLInfo: Unknown draw mode:",o);break}}function r(){t.calls=0,t.triangles=0,t.points=0,t.lines=0}return{memory:e,render:t,programs:null,autoReset:!0,reset:r,update:i}}function vC(n,e,t){let i=new WeakMap,r=new jt;function s(o,a,l){let c=o.morphTargetInfluences,u=a.morphAttributes.position||a.morphAttributes.normal||a.morphAttributes.color,h=u!==void 0?u.length:0,f=i.get(a);if(f===void 0||f.count!==h){let k=function(){y.dispose(),i.delete(a),a.removeEventListener("dispose",k)};f!==void 0&&f.texture.dispose();let d=a.morphAttributes.position!==void 0,p=a.morphAttributes.normal!==void 0,x=a.morphAttributes.color!==void 0,m=a.morphAttributes.position||[],g=a.morphAttributes.normal||[],v=a.morphAttributes.color||[],T=0;d===!0&&(T=1),p===!0&&(T=2),x===!0&&(T=3);let M=a.attributes.position.count*T,R=1;M>e.maxTextureSize&&(R=Math.ceil(M/e.maxTextureSize),M=e.maxTextureSize);let w=new Float32Array(M*R*4*h),y=new gl(w,M,R,h);y.type=er,y.needsUpdate=!0;let A=T*4;for(let D=0;D<h;D++){let L=m[D],H=g[D],z=v[D],N=M*R*4*D;for(let F=0;F<L.count;F++){let Z=F*A;d===!0&&(r.fromBufferAttribute(L,F),w[N+Z+0]=r.x,w[N+Z+1]=r.y,w[N+Z+2]=r.z,w[N+Z+3]=0),p===!0&&(r.fromBufferAttribute(H,F),w[N+Z+4]=r.x,w[N+Z+5]=r.y,w[N+Z+6]=r.z,w[N+Z+7]=0),x===!0&&(r.fromBufferAttribute(z,F),w[N+Z+8]=r.x,w[N+Z+9]=r.y,w[N+Z+10]=r.z,w[N+Z+11]=z.itemSize===4?r.w:1)}}f={count:h,texture:y,size:new it(M,R)},i.set(a,f),a.addEventListener("dispose",k)}if(o.isInstancedMesh===!0&&o.morphTexture!==null)l.getUniforms().setValue(n,"morphTexture",o.morphTexture,t);else{let d=0;for(let x=0;x<c.length;x++)d+=c[x];let p=a.morphTargetsRelative?1:1-d;l.getUniforms().setValue(n,"morphTargetBaseInfluence",p),l.getUniforms().setValue(n,"morphTargetInfluences",c)}l.getUniforms().setValue(n,"morphTargetsTexture",f.texture,t),l.getUniforms().setValue(n,"morphTargetsTextureSize",f.size)}return{update:s}}function bC(n,e,t,i,r){let s=new WeakMap;function o(c){let u=r.render.frame,h=c.geometry,f=e.get(c,h);if(s.get(f)!==u&&(e.update(f),s.set(f,u)),c.isInstancedMesh&&(c.hasEventListener("dispose",l)===!1&&c.addEventListener("dispose",l),s.get(c)!==u&&(t.update(c.instanceMatrix,n.ARRAY_BUFFER),c.instanceColor!==null&&t.update(c.instanceColor,n.ARRAY_BUFFER),s.set(c,u))),c.isSkinnedMesh){let d=c.skeleton;s.get(d)!==u&&(d.update(),s.set(d,u))}return f}function a(){s=new WeakMap}function l(c){let u=c.target;u.removeEventListener("dispose",l),i.releaseStatesOfObject(u),t.remove(u.instanceMatrix),u.instanceColor!==null&&t.remove(u.instanceColor)}return{update:o,dispose:a}}var SC={[cm]:"LINEAR_TONE_MAPPING",[um]:"REINHARD_TONE_MAPPING",[hm]:"CINEON_TONE_MAPPING",[fm]:"ACES_FILMIC_TONE_MAPPING",[pm]:"AGX_TONE_MAPPING",[mm]:"NEUTRAL_TONE_MAPPING",[dm]:"CUSTOM_TONE_MAPPING"};function MC(n,e,t,i,r,s){let o=new Ai(e,t,{type:n,depthBuffer:r,stencilBuffer:s,samples:i?4:0,storeMultisampledDepthBuffer:!1,storeMultisampledStencilBuffer:!1,resolveDepthBuffer:!1,resolveStencilBuffer:!1}),a=null,l=null,c=null,u=new ci;u.setAttribute("position",new qn([-1,3,0,-1,-1,0,3,-1,0],3)),u.setAttribute("uv",new qn([0,2,0,0,2,0],2));let h=new ih({uniforms:{tDiffuse:{value:null}},vertexShader:`
			precision highp float;

			uniform mat4 modelViewMatrix;
			uniform mat4 projectionMatrix;

			attribute vec3 position;
			attribute vec2 uv;

			varying vec2 vUv;

			void main() {
				vUv = uv;
				gl_Position = projectionMatrix * modelViewMatrix * vec4( position, 1.0 );
			}`,fragmentShader:`
			precision highp float;

			uniform sampler2D tDiffuse;

			varying vec2 vUv;

			#include <tonemapping_pars_fragment>
			#include <colorspace_pars_fragment>

			void main() {
				gl_FragColor = texture2D( tDiffuse, vUv );

				#ifdef LINEAR_TONE_MAPPING
					gl_FragColor.rgb = LinearToneMapping( gl_FragColor.rgb );
				#elif defined( REINHARD_TONE_MAPPING )
					gl_FragColor.rgb = ReinhardToneMapping( gl_FragColor.rgb );
				#elif defined( CINEON_TONE_MAPPING )
					gl_FragColor.rgb = CineonToneMapping( gl_FragColor.rgb );
				#elif defined( ACES_FILMIC_TONE_MAPPING )
					gl_FragColor.rgb = ACESFilmicToneMapping( gl_FragColor.rgb );
				#elif defined( AGX_TONE_MAPPING )
					gl_FragColor.rgb = AgXToneMapping( gl_FragColor.rgb );
				#elif defined( NEUTRAL_TONE_MAPPING )
					gl_FragColor.rgb = NeutralToneMapping( gl_FragColor.rgb );
				#elif defined( CUSTOM_TONE_MAPPING )
					gl_FragColor.rgb = CustomToneMapping( gl_FragColor.rgb );
				#endif

				#ifdef SRGB_TRANSFER
					gl_FragColor = sRGBTransferOETF( gl_FragColor );
				#endif
			}`,depthTest:!1,depthWrite:!1}),f=new Ti(u,h),d=new Nl(-1,1,1,-1,0,1),p=null,x=null,m=!1,g,v=null,T=[],M=!1;this.setSize=function(R,w){o.setSize(R,w),a!==null&&a.setSize(R,w),l!==null&&l.setSize(R,w);for(let y=0;y<T.length;y++){let A=T[y];A.setSize&&A.setSize(R,w)}},this.setEffects=function(R){T=R,M=T.length>0&&T[0].isRenderPass===!0;let w=o.width,y=o.height;T.length>0&&a===null&&(a=new Ai(w,y,{type:tr,depthBuffer:!1,stencilBuffer:!1}),l=new Ai(w,y,{type:tr,depthBuffer:!1,stencilBuffer:!1}));let A=r===!0&&T.some(k=>k.needsDepthTexture===!0);A!==(o.depthTexture!==null)&&(A===!0&&c===null&&(c=new Wr(w,y),s===!0&&(c.format=Yr,c.type=$s)),o.dispose(),o.depthTexture=A?c:null,o.resolveDepthBuffer=A,o.storeMultisampledDepthBuffer=A);for(let k=0;k<T.length;k++){let D=T[k];D.setSize&&D.setSize(w,y),A&&D.needsDepthTexture===!0&&D.setDepthTexture&&D.setDepthTexture(c)}},this.begin=function(R,w){if(m||R.toneMapping===br&&T.length===0)return!1;if(v=w,w!==null){let y=w.width,A=w.height;(o.width!==y||o.height!==A)&&this.setSize(y,A)}return M===!1&&R.setRenderTarget(o),g=R.toneMapping,R.toneMapping=br,!0},this.hasRenderPass=function(){return M},this.end=function(R,w){R.toneMapping=g,m=!0;let y=o,A=a;for(let k=0;k<T.length;k++){let D=T[k];D.enabled!==!1&&(D.render(R,A,y,w),D.needsSwap!==!1&&(y=A,A=A===a?l:a))}if(p!==R.outputColorSpace||x!==R.toneMapping){p=R.outputColorSpace,x=R.toneMapping,h.defines={},vt.getTransfer(p)===Nt&&(h.defines.SRGB_TRANSFER="");let k=SC[x];k&&(h.defines[k]=""),h.needsUpdate=!0}h.uniforms.tDiffuse.value=y.texture,R.setRenderTarget(v),R.render(f,d),v=null,m=!1},this.isCompositing=function(){return m},this.dispose=function(){o.dispose(),a!==null&&a.dispose(),l!==null&&l.dispose(),u.dispose(),h.dispose()}}var Kb=new fi,$b=new Wr(1,1),qb=new El(1),Jb=new gl,jb=new Ju,Qb=new Ml,Tb=[],Rb=[],Ib=new Float32Array(16),Cb=new Float32Array(9),Nb=new Float32Array(4);function da(n,e,t){let i=n[0];if(i<=0||i>0)return n;let r=e*t,s=Tb[r];if(s===void 0&&(s=new Float32Array(r),Tb[r]=s),e!==0){i.toArray(s,0);for(let o=1,a=0;o!==e;++o)a+=t,n[o].toArray(s,a)}return s}function In(n,e){if(n.length!==e.length)return!1;for(let t=0,i=n.length;t<i;t++)if(n[t]!==e[t])return!1;return!0}function Cn(n,e){for(let t=0,i=e.length;t<i;t++)n[t]=e[t]}function uf(n,e){let t=Rb[e];t===void 0&&(t=new Int32Array(e),Rb[e]=t);for(let i=0;i!==e;++i)t[i]=n.allocateTextureUnit();return t}function EC(n,e){let t=this.cache;t[0]!==e&&(n.uniform1f(this.addr,e),t[0]=e)}function wC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y)&&(n.uniform2f(this.addr,e.x,e.y),t[0]=e.x,t[1]=e.y);else{if(In(t,e))return;n.uniform2fv(this.addr,e),Cn(t,e)}}function AC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z)&&(n.uniform3f(this.addr,e.x,e.y,e.z),t[0]=e.x,t[1]=e.y,t[2]=e.z);else if(e.r!==void 0)(t[0]!==e.r||t[1]!==e.g||t[2]!==e.b)&&(n.uniform3f(this.addr,e.r,e.g,e.b),t[0]=e.r,t[1]=e.g,t[2]=e.b);else{if(In(t,e))return;n.uniform3fv(this.addr,e),Cn(t,e)}}function TC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z||t[3]!==e.w)&&(n.uniform4f(this.addr,e.x,e.y,e.z,e.w),t[0]=e.x,t[1]=e.y,t[2]=e.z,t[3]=e.w);else{if(In(t,e))return;n.uniform4fv(this.addr,e),Cn(t,e)}}function RC(n,e){let t=this.cache,i=e.elements;if(i===void 0){if(In(t,e))return;n.uniformMatrix2fv(this.addr,!1,e),Cn(t,e)}else{if(In(t,i))return;Nb.set(i),n.uniformMatrix2fv(this.addr,!1,Nb),Cn(t,i)}}function IC(n,e){let t=this.cache,i=e.elements;if(i===void 0){if(In(t,e))return;n.uniformMatrix3fv(this.addr,!1,e),Cn(t,e)}else{if(In(t,i))return;Cb.set(i),n.uniformMatrix3fv(this.addr,!1,Cb),Cn(t,i)}}function CC(n,e){let t=this.cache,i=e.elements;if(i===void 0){if(In(t,e))return;n.uniformMatrix4fv(this.addr,!1,e),Cn(t,e)}else{if(In(t,i))return;Ib.set(i),n.uniformMatrix4fv(this.addr,!1,Ib),Cn(t,i)}}function NC(n,e){let t=this.cache;t[0]!==e&&(n.uniform1i(this.addr,e),t[0]=e)}function PC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y)&&(n.uniform2i(this.addr,e.x,e.y),t[0]=e.x,t[1]=e.y);else{if(In(t,e))return;n.uniform2iv(this.addr,e),Cn(t,e)}}function LC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z)&&(n.uniform3i(this.addr,e.x,e.y,e.z),t[0]=e.x,t[1]=e.y,t[2]=e.z);else{if(In(t,e))return;n.uniform3iv(this.addr,e),Cn(t,e)}}function DC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z||t[3]!==e.w)&&(n.uniform4i(this.addr,e.x,e.y,e.z,e.w),t[0]=e.x,t[1]=e.y,t[2]=e.z,t[3]=e.w);else{if(In(t,e))return;n.uniform4iv(this.addr,e),Cn(t,e)}}function UC(n,e){let t=this.cache;t[0]!==e&&(n.uniform1ui(this.addr,e),t[0]=e)}function OC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y)&&(n.uniform2ui(this.addr,e.x,e.y),t[0]=e.x,t[1]=e.y);else{if(In(t,e))return;n.uniform2uiv(this.addr,e),Cn(t,e)}}function FC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z)&&(n.uniform3ui(this.addr,e.x,e.y,e.z),t[0]=e.x,t[1]=e.y,t[2]=e.z);else{if(In(t,e))return;n.uniform3uiv(this.addr,e),Cn(t,e)}}function BC(n,e){let t=this.cache;if(e.x!==void 0)(t[0]!==e.x||t[1]!==e.y||t[2]!==e.z||t[3]!==e.w)&&(n.uniform4ui(this.addr,e.x,e.y,e.z,e.w),t[0]=e.x,t[1]=e.y,t[2]=e.z,t[3]=e.w);else{if(In(t,e))return;n.uniform4uiv(this.addr,e),Cn(t,e)}}function hf(n){return n.version===0&&(n.compareFunction=Am,n.needsUpdate=!0),n}function kC(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r);let s;this.type===n.SAMPLER_2D_SHADOW?s=hf($b):s=Kb,t.setTexture2D(e||s,r)}function VC(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r),t.setTexture3D(e||jb,r)}function GC(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r);let s;this.type===n.SAMPLER_CUBE_SHADOW?s=hf(qb):s=Qb,t.setTextureCube(e||s,r)}function zC(n,e,t){let i=this.cache,r=t.allocateTextureUnit();i[0]!==r&&(n.uniform1i(this.addr,r),i[0]=r),t.setTexture2DArray(e||Jb,r)}function HC(n){switch(n){case 5126:return EC;case 35664:return wC;case 35665:return AC;case 35666:return TC;case 35674:return RC;case 35675:return IC;case 35676:return CC;case 5124:case 35670:return NC;case 35667:case 35671:return PC;case 35668:case 35672:return LC;case 35669:case 35673:return DC;case 5125:return UC;case 36294:return OC;case 36295:return FC;case 36296:return BC;case 35678:case 36198:case 36298:case 36306:case 35682:return kC;case 35679:case 36299:case 36307:return VC;case 35680:case 36300:case 36308:case 36293:return GC;case 36289:case 36303:case 36311:case 36292:return zC}}function WC(n,e){n.uniform1fv(this.addr,e)}function XC(n,e){let t=da(e,this.size,2);n.uniform2fv(this.addr,t)}function YC(n,e){let t=da(e,this.size,3);n.uniform3fv(this.addr,t)}function ZC(n,e){let t=da(e,this.size,4);n.uniform4fv(this.addr,t)}function KC(n,e){let t=da(e,this.size,4);n.uniformMatrix2fv(this.addr,!1,t)}function $C(n,e){let t=da(e,this.size,9);n.uniformMatrix3fv(this.addr,!1,t)}function qC(n,e){let t=da(e,this.size,16);n.uniformMatrix4fv(this.addr,!1,t)}function JC(n,e){n.uniform1iv(this.addr,e)}function jC(n,e){n.uniform2iv(this.addr,e)}function QC(n,e){n.uniform3iv(this.addr,e)}function eN(n,e){n.uniform4iv(this.addr,e)}function tN(n,e){n.uniform1uiv(this.addr,e)}function nN(n,e){n.uniform2uiv(this.addr,e)}function iN(n,e){n.uniform3uiv(this.addr,e)}function rN(n,e){n.uniform4uiv(this.addr,e)}function sN(n,e,t){let i=this.cache,r=e.length,s=uf(t,r);In(i,s)||(n.uniform1iv(this.addr,s),Cn(i,s));let o;this.type===n.SAMPLER_2D_SHADOW?o=hf($b):o=Kb;for(let a=0;a!==r;++a)t.setTexture2D(e[a]||o,s[a])}function oN(n,e,t){let i=this.cache,r=e.length,s=uf(t,r);In(i,s)||(n.uniform1iv(this.addr,s),Cn(i,s));for(let o=0;o!==r;++o)t.setTexture3D(e[o]||jb,s[o])}function aN(n,e,t){let i=this.cache,r=e.length,s=uf(t,r);In(i,s)||(n.uniform1iv(this.addr,s),Cn(i,s));let o;this.type===n.SAMPLER_CUBE_SHADOW?o=hf(qb):o=Qb;for(let a=0;a!==r;++a)t.setTextureCube(e[a]||o,s[a])}function lN(n,e,t){let i=this.cache,r=e.length,s=uf(t,r);In(i,s)||(n.uniform1iv(this.addr,s),Cn(i,s));for(let o=0;o!==r;++o)t.setTexture2DArray(e[o]||Jb,s[o])}function cN(n){switch(n){case 5126:return WC;case 35664:return XC;case 35665:return YC;case 35666:return ZC;case 35674:return KC;case 35675:return $C;case 35676:return qC;case 5124:case 35670:return JC;case 35667:case 35671:return jC;case 35668:case 35672:return QC;case 35669:case 35673:return eN;case 5125:return tN;case 36294:return nN;case 36295:return iN;case 36296:return rN;case 35678:case 36198:case 36298:case 36306:case 35682:return sN;case 35679:case 36299:case 36307:return oN;case 35680:case 36300:case 36308:case 36293:return aN;case 36289:case 36303:case 36311:case 36292:return lN}}var km=class{constructor(e,t,i){this.id=e,this.addr=i,this.cache=[],this.type=t.type,this.setValue=HC(t.type)}},Vm=class{constructor(e,t,i){this.id=e,this.addr=i,this.cache=[],this.type=t.type,this.size=t.size,this.setValue=cN(t.type)}},Gm=class{constructor(e){this.id=e,this.seq=[],this.map={}}setValue(e,t,i){let r=this.seq;for(let s=0,o=r.length;s!==o;++s){let a=r[s];a.setValue(e,t[a.id],i)}}},Fm=/(\w+)(\])?(\[|\.)?/g;function Pb(n,e){n.seq.push(e),n.map[e.id]=e}function uN(n,e,t){let i=n.name,r=i.length;for(Fm.lastIndex=0;;){let s=Fm.exec(i),o=Fm.lastIndex,a=s[1],l=s[2]==="]",c=s[3];if(l&&(a=a|0),c===void 0||c==="["&&o+2===r){Pb(t,c===void 0?new km(a,n,e):new Vm(a,n,e));break}else{let h=t.map[a];h===void 0&&(h=new Gm(a),Pb(t,h)),t=h}}}var fa=class{constructor(e,t){this.seq=[],this.map={};let i=e.getProgramParameter(t,e.ACTIVE_UNIFORMS);for(let o=0;o<i;++o){let a=e.getActiveUniform(t,o),l=e.getUniformLocation(t,a.name);uN(a,l,this)}let r=[],s=[];for(let o of this.seq)o.type===e.SAMPLER_2D_SHADOW||o.type===e.SAMPLER_CUBE_SHADOW||o.type===e.SAMPLER_2D_ARRAY_SHADOW?r.push(o):s.push(o);r.length>0&&(this.seq=r.concat(s))}setValue(e,t,i,r){let s=this.map[t];s!==void 0&&s.setValue(e,i,r)}setOptional(e,t,i){let r=t[i];r!==void 0&&this.setValue(e,i,r)}static upload(e,t,i,r){for(let s=0,o=t.length;s!==o;++s){let a=t[s],l=i[a.id];l.needsUpdate!==!1&&a.setValue(e,l.value,r)}}static seqWithValue(e,t){let i=[];for(let r=0,s=e.length;r!==s;++r){let o=e[r];o.id in t&&i.push(o)}return i}};function Lb(n,e,t){let i=n.createShader(e);return n.shaderSource(i,t),n.compileShader(i),i}var hN=37297,fN=0;function dN(n,e){let t=n.split(`
`),i=[],r=Math.max(e-6,0),s=Math.min(e+6,t.length);for(let o=r;o<s;o++){let a=o+1;i.push(`${a===e?">":" "} ${a}: ${t[o]}`)}return i.join(`
`)}var Db=new rt;function pN(n){vt._getMatrix(Db,vt.workingColorSpace,n);let e=`mat3( ${Db.elements.map(t=>t.toFixed(4))} )`;switch(vt.getTransfer(n)){case pl:return[e,"LinearTransferOETF"];case Nt:return[e,"sRGBTransferOETF"];default:return Ke("WebGLProgram: Unsupported color space: ",n),[e,"LinearTransferOETF"]}}function Ub(n,e,t){let i=n.getShaderParameter(e,n.COMPILE_STATUS),s=(n.getShaderInfoLog(e)||"").trim();if(i&&s==="")return"";let o=/ERROR: 0:(\d+)/.exec(s);if(o){let a=parseInt(o[1]);return t.toUpperCase()+`

`+s+`

`+dN(n.getShaderSource(e),a)}else return s}function mN(n,e){let t=pN(e);return[`vec4 ${n}( vec4 value ) {`,`	return ${t[1]}( vec4( ${t[0]} * value.rgb, value.a ) );`,"}"].join(`
`)}var gN={[cm]:"Linear",[um]:"Reinhard",[hm]:"Cineon",[fm]:"ACESFilmic",[pm]:"AgX",[mm]:"Neutral",[dm]:"Custom"};function yN(n,e){let t=gN[e];return t===void 0?(Ke("WebGLProgram: Unsupported toneMapping:",e),"vec3 "+n+"( vec3 color ) { return LinearToneMapping( color ); }"):"vec3 "+n+"( vec3 color ) { return "+t+"ToneMapping( color ); }"}var af=new Y;function _N(){vt.getLuminanceCoefficients(af);let n=af.x.toFixed(4),e=af.y.toFixed(4),t=af.z.toFixed(4);return["float luminance( const in vec3 rgb ) {",`	const vec3 weights = vec3( ${n}, ${e}, ${t} );`,"	return dot( weights, rgb );","}"].join(`
`)}function xN(n){return[n.extensionClipCullDistance?"#extension GL_ANGLE_clip_cull_distance : require":"",n.extensionMultiDraw?"#extension GL_ANGLE_multi_draw : require":""].filter(Hl).join(`
`)}function vN(n){let e=[];for(let t in n){let i=n[t];i!==!1&&e.push("#define "+t+" "+i)}return e.join(`
`)}function bN(n,e){let t={},i=n.getProgramParameter(e,n.ACTIVE_ATTRIBUTES);for(let r=0;r<i;r++){let s=n.getActiveAttrib(e,r),o=s.name,a=1;s.type===n.FLOAT_MAT2&&(a=2),s.type===n.FLOAT_MAT3&&(a=3),s.type===n.FLOAT_MAT4&&(a=4),t[o]={type:s.type,location:n.getAttribLocation(e,o),locationSize:a}}return t}function Hl(n){return n!==""}function Ob(n,e){let t=e.numSpotLightShadows+e.numSpotLightMaps-e.numSpotLightShadowsWithMaps;return n.replace(/NUM_SUN_LIGHTS/g,e.numSunLights).replace(/NUM_DIR_LIGHTS/g,e.numDirLights).replace(/NUM_SPOT_LIGHTS/g,e.numSpotLights).replace(/NUM_SPOT_LIGHT_MAPS/g,e.numSpotLightMaps).replace(/NUM_SPOT_LIGHT_COORDS/g,t).replace(/NUM_RECT_AREA_LIGHTS/g,e.numRectAreaLights).replace(/NUM_POINT_LIGHTS/g,e.numPointLights).replace(/NUM_HEMI_LIGHTS/g,e.numHemiLights).replace(/NUM_SUN_LIGHT_SHADOWS/g,e.numSunLightShadows).replace(/NUM_DIR_LIGHT_SHADOWS/g,e.numDirLightShadows).replace(/NUM_SPOT_LIGHT_SHADOWS_WITH_MAPS/g,e.numSpotLightShadowsWithMaps).replace(/NUM_SPOT_LIGHT_SHADOWS/g,e.numSpotLightShadows).replace(/NUM_POINT_LIGHT_SHADOWS/g,e.numPointLightShadows).replace(/NUM_LIGHT_PROBE_GRIDS/g,e.numLightProbeGrids)}function Fb(n,e){return n.replace(/NUM_CLIPPING_PLANES/g,e.numClippingPlanes).replace(/UNION_CLIPPING_PLANES/g,e.numClippingPlanes-e.numClipIntersection)}var SN=/^[ \t]*#include +<([\w\d./]+)>/gm;function zm(n){return n.replace(SN,MN)}function MN(n,e){let t=dt[e];if(t===void 0)throw new Error("THREE.WebGLProgram: Can not resolve #include <"+e+">");return zm(t)}var EN=/#pragma unroll_loop_start\s+for\s*\(\s*int\s+i\s*=\s*(\d+)\s*;\s*i\s*<\s*(\d+)\s*;\s*i\s*\+\+\s*\)\s*{([\s\S]+?)}\s+#pragma unroll_loop_end/g;function Bb(n){return n.replace(EN,wN)}function wN(n,e,t,i){let r="";for(let s=parseInt(e);s<parseInt(t);s++)r+=i.replace(/\[\s*i\s*\]/g,"[ "+s+" ]").replace(/UNROLLED_LOOP_INDEX/g,s);return r}function kb(n){let e=`precision ${n.precision} float;
	precision ${n.precision} int;
	precision ${n.precision} sampler2D;
	precision ${n.precision} samplerCube;
	precision ${n.precision} sampler3D;
	precision ${n.precision} sampler2DArray;
	precision ${n.precision} sampler2DShadow;
	precision ${n.precision} samplerCubeShadow;
	precision ${n.precision} sampler2DArrayShadow;
	precision ${n.precision} isampler2D;
	precision ${n.precision} isampler3D;
	precision ${n.precision} isamplerCube;
	precision ${n.precision} isampler2DArray;
	precision ${n.precision} usampler2D;
	precision ${n.precision} usampler3D;
	precision ${n.precision} usamplerCube;
	precision ${n.precision} usampler2DArray;
	`;return n.precision==="highp"?e+=`
#define HIGH_PRECISION`:n.precision==="mediump"?e+=`
#define MEDIUM_PRECISION`:n.precision==="lowp"&&(e+=`
#define LOW_PRECISION`),e}var AN={[Dl]:"SHADOWMAP_TYPE_PCF",[aa]:"SHADOWMAP_TYPE_VSM"};function TN(n){return AN[n.shadowMapType]||"SHADOWMAP_TYPE_BASIC"}var RN={[ca]:"ENVMAP_MODE_REFRACTION"};function IN(n){return n.envMap===!1?"ENVMAP_MODE_REFLECTION":RN[n.envMapMode]||"ENVMAP_MODE_REFLECTION"}var CN={[_h]:"ENVMAP_BLENDING_MULTIPLY",[tb]:"ENVMAP_BLENDING_MIX",[nb]:"ENVMAP_BLENDING_ADD"};function NN(n){return n.envMap===!1?"ENVMAP_BLENDING_NONE":CN[n.combine]||"ENVMAP_BLENDING_NONE"}function PN(n,e,t,i){let r=n.getContext(),s=t.defines,o=t.vertexShader,a=t.fragmentShader,l=TN(t),c=t.envMapPMREM===!0?"ENVMAP_TYPE_PMREM":"ENVMAP_TYPE_CUBE",u=IN(t),h=NN(t),f=xN(t),d=vN(s),p=r.createProgram(),x,m,g=t.glslVersion?"#version "+t.glslVersion+`
`:"";t.isRawShaderMaterial?(x=["#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d].filter(Hl).join(`
`),x.length>0&&(x+=`
`),m=["#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d].filter(Hl).join(`
`),m.length>0&&(m+=`
`)):(x=[kb(t),"#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d,t.extensionClipCullDistance?"#define USE_CLIP_DISTANCE":"",t.batching?"#define USE_BATCHING":"",t.batchingColor?"#define USE_BATCHING_COLOR":"",t.instancing?"#define USE_INSTANCING":"",t.instancingColor?"#define USE_INSTANCING_COLOR":"",t.instancingMorph?"#define USE_INSTANCING_MORPH":"",t.useFog&&t.fog?"#define USE_FOG":"",t.useFog&&t.fogExp2?"#define FOG_EXP2":"",t.map?"#define USE_MAP":"",t.envMap?"#define USE_ENVMAP":"",t.envMap?"#define "+u:"",t.lightMap?"#define USE_LIGHTMAP":"",t.aoMap?"#define USE_AOMAP":"",t.bumpMap?"#define USE_BUMPMAP":"",t.normalMap?"#define USE_NORMALMAP":"",t.normalMapObjectSpace?"#define USE_NORMALMAP_OBJECTSPACE":"",t.normalMapTangentSpace?"#define USE_NORMALMAP_TANGENTSPACE":"",t.displacementMap?"#define USE_DISPLACEMENTMAP":"",t.emissiveMap?"#define USE_EMISSIVEMAP":"",t.anisotropy?"#define USE_ANISOTROPY":"",t.anisotropyMap?"#define USE_ANISOTROPYMAP":"",t.clearcoatMap?"#define USE_CLEARCOATMAP":"",t.clearcoatRoughnessMap?"#define USE_CLEARCOAT_ROUGHNESSMAP":"",t.clearcoatNormalMap?"#define USE_CLEARCOAT_NORMALMAP":"",t.diffuseRoughnessMap?"#define USE_DIFFUSE_ROUGHNESSMAP":"",t.iridescenceMap?"#define USE_IRIDESCENCEMAP":"",t.iridescenceThicknessMap?"#define USE_IRIDESCENCE_THICKNESSMAP":"",t.specularMap?"#define USE_SPECULARMAP":"",t.specularColorMap?"#define USE_SPECULAR_COLORMAP":"",t.specularIntensityMap?"#define USE_SPECULAR_INTENSITYMAP":"",t.roughnessMap?"#define USE_ROUGHNESSMAP":"",t.metalnessMap?"#define USE_METALNESSMAP":"",t.alphaMap?"#define USE_ALPHAMAP":"",t.alphaHash?"#define USE_ALPHAHASH":"",t.transmission?"#define USE_TRANSMISSION":"",t.transmissionMap?"#define USE_TRANSMISSIONMAP":"",t.thicknessMap?"#define USE_THICKNESSMAP":"",t.sheenColorMap?"#define USE_SHEEN_COLORMAP":"",t.sheenRoughnessMap?"#define USE_SHEEN_ROUGHNESSMAP":"",t.mapUv?"#define MAP_UV "+t.mapUv:"",t.alphaMapUv?"#define ALPHAMAP_UV "+t.alphaMapUv:"",t.lightMapUv?"#define LIGHTMAP_UV "+t.lightMapUv:"",t.aoMapUv?"#define AOMAP_UV "+t.aoMapUv:"",t.emissiveMapUv?"#define EMISSIVEMAP_UV "+t.emissiveMapUv:"",t.bumpMapUv?"#define BUMPMAP_UV "+t.bumpMapUv:"",t.normalMapUv?"#define NORMALMAP_UV "+t.normalMapUv:"",t.displacementMapUv?"#define DISPLACEMENTMAP_UV "+t.displacementMapUv:"",t.metalnessMapUv?"#define METALNESSMAP_UV "+t.metalnessMapUv:"",t.roughnessMapUv?"#define ROUGHNESSMAP_UV "+t.roughnessMapUv:"",t.anisotropyMapUv?"#define ANISOTROPYMAP_UV "+t.anisotropyMapUv:"",t.clearcoatMapUv?"#define CLEARCOATMAP_UV "+t.clearcoatMapUv:"",t.clearcoatNormalMapUv?"#define CLEARCOAT_NORMALMAP_UV "+t.clearcoatNormalMapUv:"",t.clearcoatRoughnessMapUv?"#define CLEARCOAT_ROUGHNESSMAP_UV "+t.clearcoatRoughnessMapUv:"",t.diffuseRoughnessMapUv?"#define DIFFUSE_ROUGHNESSMAP_UV "+t.diffuseRoughnessMapUv:"",t.iridescenceMapUv?"#define IRIDESCENCEMAP_UV "+t.iridescenceMapUv:"",t.iridescenceThicknessMapUv?"#define IRIDESCENCE_THICKNESSMAP_UV "+t.iridescenceThicknessMapUv:"",t.sheenColorMapUv?"#define SHEEN_COLORMAP_UV "+t.sheenColorMapUv:"",t.sheenRoughnessMapUv?"#define SHEEN_ROUGHNESSMAP_UV "+t.sheenRoughnessMapUv:"",t.specularMapUv?"#define SPECULARMAP_UV "+t.specularMapUv:"",t.specularColorMapUv?"#define SPECULAR_COLORMAP_UV "+t.specularColorMapUv:"",t.specularIntensityMapUv?"#define SPECULAR_INTENSITYMAP_UV "+t.specularIntensityMapUv:"",t.transmissionMapUv?"#define TRANSMISSIONMAP_UV "+t.transmissionMapUv:"",t.thicknessMapUv?"#define THICKNESSMAP_UV "+t.thicknessMapUv:"",t.vertexTangents&&t.flatShading===!1?"#define USE_TANGENT":"",t.vertexNormals?"#define HAS_NORMAL":"",t.vertexColors?"#define USE_COLOR":"",t.vertexAlphas?"#define USE_COLOR_ALPHA":"",t.vertexUv1s?"#define USE_UV1":"",t.vertexUv2s?"#define USE_UV2":"",t.vertexUv3s?"#define USE_UV3":"",t.pointsUvs?"#define USE_POINTS_UV":"",t.flatShading?"#define FLAT_SHADED":"",t.skinning?"#define USE_SKINNING":"",t.morphTargets?"#define USE_MORPHTARGETS":"",t.morphNormals&&t.flatShading===!1?"#define USE_MORPHNORMALS":"",t.morphColors?"#define USE_MORPHCOLORS":"",t.morphTargetsCount>0?"#define MORPHTARGETS_TEXTURE_STRIDE "+t.morphTextureStride:"",t.morphTargetsCount>0?"#define MORPHTARGETS_COUNT "+t.morphTargetsCount:"",t.doubleSided?"#define DOUBLE_SIDED":"",t.flipSided?"#define FLIP_SIDED":"",t.shadowMapEnabled?"#define USE_SHADOWMAP":"",t.shadowMapEnabled?"#define "+l:"",t.sizeAttenuation?"#define USE_SIZEATTENUATION":"",t.numLightProbes>0?"#define USE_LIGHT_PROBES":"",t.logarithmicDepthBuffer?"#define USE_LOGARITHMIC_DEPTH_BUFFER":"",t.reversedDepthBuffer?"#define USE_REVERSED_DEPTH_BUFFER":"","uniform mat4 modelMatrix;","uniform mat4 modelViewMatrix;","uniform mat4 projectionMatrix;","uniform mat4 viewMatrix;","uniform mat3 normalMatrix;","uniform vec3 cameraPosition;","uniform bool isOrthographic;","#ifdef USE_INSTANCING","	attribute mat4 instanceMatrix;","#endif","#ifdef USE_INSTANCING_COLOR","	attribute vec3 instanceColor;","#endif","#ifdef USE_INSTANCING_MORPH","	uniform sampler2D morphTexture;","#endif","attribute vec3 position;","attribute vec3 normal;","attribute vec2 uv;","#ifdef USE_UV1","	attribute vec2 uv1;","#endif","#ifdef USE_UV2","	attribute vec2 uv2;","#endif","#ifdef USE_UV3","	attribute vec2 uv3;","#endif","#ifdef USE_TANGENT","	attribute vec4 tangent;","#endif","#if defined( USE_COLOR_ALPHA )","	attribute vec4 color;","#elif defined( USE_COLOR )","	attribute vec3 color;","#endif","#ifdef USE_SKINNING","	attribute vec4 skinIndex;","	attribute vec4 skinWeight;","#endif",`
`].filter(Hl).join(`
`),m=[kb(t),"#define SHADER_TYPE "+t.shaderType,"#define SHADER_NAME "+t.shaderName,d,t.useFog&&t.fog?"#define USE_FOG":"",t.useFog&&t.fogExp2?"#define FOG_EXP2":"",t.alphaToCoverage?"#define ALPHA_TO_COVERAGE":"",t.map?"#define USE_MAP":"",t.matcap?"#define USE_MATCAP":"",t.envMap?"#define USE_ENVMAP":"",t.envMap?"#define "+c:"",t.envMap?"#define "+u:"",t.envMap?"#define "+h:"",t.envMapPMREM?"#define ENVMAP_MAX_LOD "+t.envMapMaxLod+".0":"",t.envMapPMREM?"#define ENVMAP_SIZE "+t.envMapSize+".0":"",t.lightMap?"#define USE_LIGHTMAP":"",t.aoMap?"#define USE_AOMAP":"",t.bumpMap?"#define USE_BUMPMAP":"",t.normalMap?"#define USE_NORMALMAP":"",t.normalMapObjectSpace?"#define USE_NORMALMAP_OBJECTSPACE":"",t.normalMapTangentSpace?"#define USE_NORMALMAP_TANGENTSPACE":"",t.packedNormalMap?"#define USE_PACKED_NORMALMAP":"",t.emissiveMap?"#define USE_EMISSIVEMAP":"",t.anisotropy?"#define USE_ANISOTROPY":"",t.anisotropyMap?"#define USE_ANISOTROPYMAP":"",t.clearcoat?"#define USE_CLEARCOAT":"",t.clearcoatMap?"#define USE_CLEARCOATMAP":"",t.clearcoatRoughnessMap?"#define USE_CLEARCOAT_ROUGHNESSMAP":"",t.clearcoatNormalMap?"#define USE_CLEARCOAT_NORMALMAP":"",t.diffuseRoughness?"#define USE_DIFFUSE_ROUGHNESS":"",t.diffuseRoughnessMap?"#define USE_DIFFUSE_ROUGHNESSMAP":"",t.dispersion?"#define USE_DISPERSION":"",t.retroreflection?"#define USE_RETROREFLECTION":"",t.iridescence?"#define USE_IRIDESCENCE":"",t.iridescenceMap?"#define USE_IRIDESCENCEMAP":"",t.iridescenceThicknessMap?"#define USE_IRIDESCENCE_THICKNESSMAP":"",t.specularMap?"#define USE_SPECULARMAP":"",t.specularColorMap?"#define USE_SPECULAR_COLORMAP":"",t.specularIntensityMap?"#define USE_SPECULAR_INTENSITYMAP":"",t.roughnessMap?"#define USE_ROUGHNESSMAP":"",t.metalnessMap?"#define USE_METALNESSMAP":"",t.alphaMap?"#define USE_ALPHAMAP":"",t.alphaTest?"#define USE_ALPHATEST":"",t.alphaHash?"#define USE_ALPHAHASH":"",t.sheen?"#define USE_SHEEN":"",t.sheenColorMap?"#define USE_SHEEN_COLORMAP":"",t.sheenRoughnessMap?"#define USE_SHEEN_ROUGHNESSMAP":"",t.transmission?"#define USE_TRANSMISSION":"",t.transmissionMap?"#define USE_TRANSMISSIONMAP":"",t.thicknessMap?"#define USE_THICKNESSMAP":"",t.vertexTangents&&t.flatShading===!1?"#define USE_TANGENT":"",t.vertexColors||t.instancingColor?"#define USE_COLOR":"",t.vertexAlphas||t.batchingColor?"#define USE_COLOR_ALPHA":"",t.vertexUv1s?"#define USE_UV1":"",t.vertexUv2s?"#define USE_UV2":"",t.vertexUv3s?"#define USE_UV3":"",t.pointsUvs?"#define USE_POINTS_UV":"",t.gradientMap?"#define USE_GRADIENTMAP":"",t.flatShading?"#define FLAT_SHADED":"",t.doubleSided?"#define DOUBLE_SIDED":"",t.flipSided?"#define FLIP_SIDED":"",t.shadowMapEnabled?"#define USE_SHADOWMAP":"",t.shadowMapEnabled?"#define "+l:"",t.premultipliedAlpha?"#define PREMULTIPLIED_ALPHA":"",t.numLightProbes>0?"#define USE_LIGHT_PROBES":"",t.decodeVideoTexture?"#define DECODE_VIDEO_TEXTURE":"",t.decodeVideoTextureEmissive?"#define DECODE_VIDEO_TEXTURE_EMISSIVE":"",t.logarithmicDepthBuffer?"#define USE_LOGARITHMIC_DEPTH_BUFFER":"",t.reversedDepthBuffer?"#define USE_REVERSED_DEPTH_BUFFER":"","uniform mat4 viewMatrix;","uniform vec3 cameraPosition;","uniform bool isOrthographic;",t.toneMapping!==br?"#define TONE_MAPPING":"",t.toneMapping!==br?dt.tonemapping_pars_fragment:"",t.toneMapping!==br?yN("toneMapping",t.toneMapping):"",t.dithering?"#define DITHERING":"",t.opaque?"#define OPAQUE":"",dt.colorspace_pars_fragment,mN("linearToOutputTexel",t.outputColorSpace),_N(),t.useDepthPacking?"#define DEPTH_PACKING "+t.depthPacking:"",`
`].filter(Hl).join(`
`)),o=zm(o),o=Ob(o,t),o=Fb(o,t),a=zm(a),a=Ob(a,t),a=Fb(a,t),o=Bb(o),a=Bb(a),t.isRawShaderMaterial!==!0&&(g=`#version 300 es
`,x=[f,"#define attribute in","#define varying out","#define texture2D texture"].join(`
`)+`
`+x,m=["#define varying in",t.glslVersion===Tm?"":"layout(location = 0) out highp vec4 pc_fragColor;",t.glslVersion===Tm?"":"#define gl_FragColor pc_fragColor","#define gl_FragDepthEXT gl_FragDepth","#define texture2D texture","#define textureCube texture","#define texture2DProj textureProj","#define texture2DLodEXT textureLod","#define texture2DProjLodEXT textureProjLod","#define textureCubeLodEXT textureLod","#define texture2DGradEXT textureGrad","#define texture2DProjGradEXT textureProjGrad","#define textureCubeGradEXT textureGrad"].join(`
`)+`
`+m);let v=g+x+o,T=g+m+a,M=Lb(r,r.VERTEX_SHADER,v),R=Lb(r,r.FRAGMENT_SHADER,T);r.attachShader(p,M),r.attachShader(p,R),t.index0AttributeName!==void 0?r.bindAttribLocation(p,0,t.index0AttributeName):t.hasPositionAttribute===!0&&r.bindAttribLocation(p,0,"position"),r.linkProgram(p);function w(D){if(n.debug.checkShaderErrors){let L=r.getProgramInfoLog(p)||"",H=r.getShaderInfoLog(M)||"",z=r.getShaderInfoLog(R)||"",N=L.trim(),F=H.trim(),Z=z.trim(),V=!0,le=!0;if(r.getProgramParameter(p,r.LINK_STATUS)===!1)if(V=!1,typeof n.debug.onShaderError=="function")n.debug.onShaderError(r,p,M,R);else{let q=Ub(r,M,"vertex"),Q=Ub(r,R,"fragment");nt("WebGLProgram: Shader Error "+r.getError()+" - VALIDATE_STATUS "+r.getProgramParameter(p,r.VALIDATE_STATUS)+`

Material Name: `+D.name+`
Material Type: `+D.type+`

Program Info Log: `+N+`
`+q+`
`+Q)}else N!==""?Ke("WebGLProgram: Program Info Log:",N):(F===""||Z==="")&&(le=!1);le&&(D.diagnostics={runnable:V,programLog:N,vertexShader:{log:F,prefix:x},fragmentShader:{log:Z,prefix:m}})}r.deleteShader(M),r.deleteShader(R),y=new fa(r,p),A=bN(r,p)}let y;this.getUniforms=function(){return y===void 0&&w(this),y};let A;this.getAttributes=function(){return A===void 0&&w(this),A};let k=t.rendererExtensionParallelShaderCompile===!1;return this.isReady=function(){return k===!1&&(k=r.getProgramParameter(p,hN)),k},this.destroy=function(){i.releaseStatesOfProgram(this),r.deleteProgram(p),this.program=void 0},this.type=t.shaderType,this.name=t.shaderName,this.id=fN++,this.cacheKey=e,this.usedTimes=1,this.program=p,this.vertexShader=M,this.fragmentShader=R,this}var LN=0,Hm=class{constructor(){this.shaderCache=new Map,this.materialCache=new Map}update(e,t,i){let r=this._getShaderCacheForMaterial(e);return r.has(t)===!1&&(r.add(t),t.usedTimes++),r.has(i)===!1&&(r.add(i),i.usedTimes++),this}remove(e){let t=this.materialCache.get(e);for(let i of t)i.usedTimes--,i.usedTimes===0&&this.shaderCache.delete(i.code);return this.materialCache.delete(e),this}getVertexShaderStage(e){return this._getShaderStage(e.vertexShader)}getFragmentShaderStage(e){return this._getShaderStage(e.fragmentShader)}dispose(){this.shaderCache.clear(),this.materialCache.clear()}_getShaderCacheForMaterial(e){let t=this.materialCache,i=t.get(e);return i===void 0&&(i=new Set,t.set(e,i)),i}_getShaderStage(e){let t=this.shaderCache,i=t.get(e);return i===void 0&&(i=new Wm(e),t.set(e,i)),i}},Wm=class{constructor(e){this.id=LN++,this.code=e,this.usedTimes=0}};function DN(n){return n===bs||n===Vl||n===Gl}function UN(n,e,t,i,r,s){let o=new yl,a=new Hm,l=new Set,c=[],u=new Map,h=i.logarithmicDepthBuffer,f={MeshDepthMaterial:"depth",MeshDistanceMaterial:"distance",MeshNormalMaterial:"normal",MeshBasicMaterial:"basic",MeshLambertMaterial:"lambert",MeshPhongMaterial:"phong",MeshToonMaterial:"toon",MeshStandardMaterial:"physical",MeshPhysicalMaterial:"physical",MeshMatcapMaterial:"matcap",LineBasicMaterial:"basic",LineDashedMaterial:"dashed",PointsMaterial:"points",ShadowMaterial:"shadow",SpriteMaterial:"sprite"};function d(y){return l.add(y),y===0?"uv":`uv${y}`}function p(y,A,k,D,L,H){let z=D.fog,N=L.geometry,F=y.isMeshStandardMaterial||y.isMeshLambertMaterial||y.isMeshPhongMaterial?D.environment:null,Z=y.isMeshStandardMaterial||y.isMeshLambertMaterial&&!y.envMap||y.isMeshPhongMaterial&&!y.envMap,V=e.get(y.envMap||F,Z),le=f[y.type],q=i.precision;y.precision!==null&&(q=i.getMaxPrecision(y.precision),q!==y.precision&&Ke("WebGLProgram.getParameters:",y.precision,"not supported, using",q,"instead."));let Q=N.morphAttributes.position||N.morphAttributes.normal||N.morphAttributes.color,ie=Q!==void 0?Q.length:0,fe=0;N.morphAttributes.position!==void 0&&(fe=1),N.morphAttributes.normal!==void 0&&(fe=2),N.morphAttributes.color!==void 0&&(fe=3);let he,ee,ge,ye;if(le){let Ie=Mr[le];he=Ie.vertexShader,ee=Ie.fragmentShader}else{he=y.vertexShader,ee=y.fragmentShader;let Ie=a.getVertexShaderStage(y),ut=a.getFragmentShaderStage(y);a.update(y,Ie,ut),ge=Ie.id,ye=ut.id}let xe=n.getRenderTarget(),_e=n.state.buffers.depth.getReversed(),ze=L.isInstancedMesh===!0,$e=L.isBatchedMesh===!0,Fe=!!y.map,st=!!y.matcap,ct=!!V,ot=ct&&V.isPMREMTexture===!0,qt=!!y.aoMap,Gt=!!y.lightMap,hn=!!y.bumpMap&&y.wireframe===!1,Ot=!!y.normalMap,Pn=!!y.displacementMap,St=!!y.emissiveMap,En=!!y.metalnessMap,tn=!!y.roughnessMap,fn=y.anisotropy>0,O=y.clearcoat>0,Ce=y.diffuseRoughness>0,Ze=y.dispersion>0,lt=y.retroreflectivity>0,we=y.iridescence>0,Bt=y.sheen>0,He=y.transmission>0,Ye=fn&&!!y.anisotropyMap,I=O&&!!y.clearcoatMap,b=O&&!!y.clearcoatNormalMap,X=O&&!!y.clearcoatRoughnessMap,ue=Ce&&!!y.diffuseRoughnessMap,oe=we&&!!y.iridescenceMap,be=we&&!!y.iridescenceThicknessMap,Se=Bt&&!!y.sheenColorMap,te=Bt&&!!y.sheenRoughnessMap,re=!!y.specularMap,pe=!!y.specularColorMap,U=!!y.specularIntensityMap,se=He&&!!y.transmissionMap,ne=He&&!!y.thicknessMap,Ae=!!y.gradientMap,ve=!!y.alphaMap,Ee=y.alphaTest>0,We=!!y.alphaHash,je=!!y.extensions,ce=br;y.toneMapped&&(xe===null||xe.isXRRenderTarget===!0)&&(ce=n.toneMapping);let ke=ot?V.isCompressedCubeTexture?V.image[0].mipmaps:V.mipmaps:null,Qe={shaderID:le,shaderType:y.type,shaderName:y.name,vertexShader:he,fragmentShader:ee,defines:y.defines,customVertexShaderID:ge,customFragmentShaderID:ye,isRawShaderMaterial:y.isRawShaderMaterial===!0,glslVersion:y.glslVersion,precision:q,batching:$e,batchingColor:$e&&L._colorsTexture!==null,instancing:ze,instancingColor:ze&&L.instanceColor!==null,instancingMorph:ze&&L.morphTexture!==null,outputColorSpace:xe===null?n.outputColorSpace:xe.isXRRenderTarget===!0?xe.texture.colorSpace:vt.workingColorSpace,alphaToCoverage:!!y.alphaToCoverage,map:Fe,matcap:st,envMap:ct,envMapMode:ct&&V.mapping,envMapPMREM:ot,envMapMaxLod:ot?ke.length-1:null,envMapSize:ot?ke[0].width:null,aoMap:qt,lightMap:Gt,bumpMap:hn,normalMap:Ot,displacementMap:Pn,emissiveMap:St,normalMapObjectSpace:Ot&&y.normalMapType===sb,normalMapTangentSpace:Ot&&y.normalMapType===sf,packedNormalMap:Ot&&y.normalMapType===sf&&DN(y.normalMap.format),metalnessMap:En,roughnessMap:tn,anisotropy:fn,anisotropyMap:Ye,clearcoat:O,clearcoatMap:I,clearcoatNormalMap:b,clearcoatRoughnessMap:X,diffuseRoughness:Ce,diffuseRoughnessMap:ue,dispersion:Ze,retroreflection:lt,iridescence:we,iridescenceMap:oe,iridescenceThicknessMap:be,sheen:Bt,sheenColorMap:Se,sheenRoughnessMap:te,specularMap:re,specularColorMap:pe,specularIntensityMap:U,transmission:He,transmissionMap:se,thicknessMap:ne,gradientMap:Ae,opaque:y.transparent===!1&&y.blending===la&&y.alphaToCoverage===!1,alphaMap:ve,alphaTest:Ee,alphaHash:We,combine:y.combine,mapUv:Fe&&d(y.map.channel),aoMapUv:qt&&d(y.aoMap.channel),lightMapUv:Gt&&d(y.lightMap.channel),bumpMapUv:hn&&d(y.bumpMap.channel),normalMapUv:Ot&&d(y.normalMap.channel),displacementMapUv:Pn&&d(y.displacementMap.channel),emissiveMapUv:St&&d(y.emissiveMap.channel),metalnessMapUv:En&&d(y.metalnessMap.channel),roughnessMapUv:tn&&d(y.roughnessMap.channel),anisotropyMapUv:Ye&&d(y.anisotropyMap.channel),clearcoatMapUv:I&&d(y.clearcoatMap.channel),clearcoatNormalMapUv:b&&d(y.clearcoatNormalMap.channel),clearcoatRoughnessMapUv:X&&d(y.clearcoatRoughnessMap.channel),diffuseRoughnessMapUv:ue&&d(y.diffuseRoughnessMap.channel),iridescenceMapUv:oe&&d(y.iridescenceMap.channel),iridescenceThicknessMapUv:be&&d(y.iridescenceThicknessMap.channel),sheenColorMapUv:Se&&d(y.sheenColorMap.channel),sheenRoughnessMapUv:te&&d(y.sheenRoughnessMap.channel),specularMapUv:re&&d(y.specularMap.channel),specularColorMapUv:pe&&d(y.specularColorMap.channel),specularIntensityMapUv:U&&d(y.specularIntensityMap.channel),transmissionMapUv:se&&d(y.transmissionMap.channel),thicknessMapUv:ne&&d(y.thicknessMap.channel),alphaMapUv:ve&&d(y.alphaMap.channel),vertexTangents:!!N.attributes.tangent&&(Ot||fn),vertexNormals:!!N.attributes.normal,vertexColors:y.vertexColors,vertexAlphas:y.vertexColors===!0&&!!N.attributes.color&&N.attributes.color.itemSize===4,pointsUvs:L.isPoints===!0&&!!N.attributes.uv&&(Fe||ve),fog:!!z,useFog:y.fog===!0,fogExp2:!!z&&z.isFogExp2,flatShading:y.wireframe===!1&&(y.flatShading===!0||N.attributes.normal===void 0&&Ot===!1&&(y.isMeshLambertMaterial||y.isMeshPhongMaterial||y.isMeshStandardMaterial||y.isMeshPhysicalMaterial)),sizeAttenuation:y.sizeAttenuation===!0,logarithmicDepthBuffer:h,reversedDepthBuffer:_e,skinning:L.isSkinnedMesh===!0,hasPositionAttribute:N.attributes.position!==void 0,morphTargets:N.morphAttributes.position!==void 0,morphNormals:N.morphAttributes.normal!==void 0,morphColors:N.morphAttributes.color!==void 0,morphTargetsCount:ie,morphTextureStride:fe,numSunLights:A.sun.length,numDirLights:A.directional.length,numPointLights:A.point.length,numSpotLights:A.spot.length,numSpotLightMaps:A.spotLightMap.length,numRectAreaLights:A.rectArea.length,numHemiLights:A.hemi.length,numSunLightShadows:A.sunShadowMap.length,numDirLightShadows:A.directionalShadowMap.length,numPointLightShadows:A.pointShadowMap.length,numSpotLightShadows:A.spotShadowMap.length,numSpotLightShadowsWithMaps:A.numSpotLightShadowsWithMaps,numLightProbes:A.numLightProbes,numLightProbeGrids:H.filter(Ie=>Ie.texture!==null).length,numClippingPlanes:s.numPlanes,numClipIntersection:s.numIntersection,dithering:y.dithering,shadowMapEnabled:n.shadowMap.enabled&&k.length>0,shadowMapType:n.shadowMap.type,toneMapping:ce,decodeVideoTexture:Fe&&y.map.isVideoTexture===!0&&vt.getTransfer(y.map.colorSpace)===Nt,decodeVideoTextureEmissive:St&&y.emissiveMap.isVideoTexture===!0&&vt.getTransfer(y.emissiveMap.colorSpace)===Nt,premultipliedAlpha:y.premultipliedAlpha,doubleSided:y.side===Fi,flipSided:y.side===ui,useDepthPacking:y.depthPacking>=0,depthPacking:y.depthPacking||0,index0AttributeName:y.index0AttributeName,extensionClipCullDistance:je&&y.extensions.clipCullDistance===!0&&t.has("WEBGL_clip_cull_distance"),extensionMultiDraw:(je&&y.extensions.multiDraw===!0||$e)&&t.has("WEBGL_multi_draw"),rendererExtensionParallelShaderCompile:t.has("KHR_parallel_shader_compile"),customProgramCacheKey:y.customProgramCacheKey()};return Qe.vertexUv1s=l.has(1),Qe.vertexUv2s=l.has(2),Qe.vertexUv3s=l.has(3),l.clear(),Qe}function x(y){let A=[];if(y.shaderID?A.push(y.shaderID):(A.push(y.customVertexShaderID),A.push(y.customFragmentShaderID)),y.defines!==void 0)for(let k in y.defines)A.push(k),A.push(y.defines[k]);return y.isRawShaderMaterial===!1&&(m(A,y),g(A,y),A.push(n.outputColorSpace)),A.push(y.customProgramCacheKey),A.join()}function m(y,A){y.push(A.precision),y.push(A.outputColorSpace),y.push(A.envMapMode),y.push(A.envMapPMREM),y.push(A.envMapMaxLod),y.push(A.envMapSize),y.push(A.mapUv),y.push(A.alphaMapUv),y.push(A.lightMapUv),y.push(A.aoMapUv),y.push(A.bumpMapUv),y.push(A.normalMapUv),y.push(A.displacementMapUv),y.push(A.emissiveMapUv),y.push(A.metalnessMapUv),y.push(A.roughnessMapUv),y.push(A.anisotropyMapUv),y.push(A.clearcoatMapUv),y.push(A.clearcoatNormalMapUv),y.push(A.clearcoatRoughnessMapUv),y.push(A.diffuseRoughnessMapUv),y.push(A.iridescenceMapUv),y.push(A.iridescenceThicknessMapUv),y.push(A.sheenColorMapUv),y.push(A.sheenRoughnessMapUv),y.push(A.specularMapUv),y.push(A.specularColorMapUv),y.push(A.specularIntensityMapUv),y.push(A.transmissionMapUv),y.push(A.thicknessMapUv),y.push(A.combine),y.push(A.fogExp2),y.push(A.sizeAttenuation),y.push(A.morphTargetsCount),y.push(A.numSunLights),y.push(A.numDirLights),y.push(A.numPointLights),y.push(A.numSpotLights),y.push(A.numSpotLightMaps),y.push(A.numHemiLights),y.push(A.numRectAreaLights),y.push(A.numSunLightShadows),y.push(A.numDirLightShadows),y.push(A.numPointLightShadows),y.push(A.numSpotLightShadows),y.push(A.numSpotLightShadowsWithMaps),y.push(A.numLightProbes),y.push(A.numLightProbeGrids),y.push(A.shadowMapType),y.push(A.toneMapping),y.push(A.numClippingPlanes),y.push(A.numClipIntersection),y.push(A.depthPacking)}function g(y,A){o.disableAll(),A.instancing&&o.enable(0),A.instancingColor&&o.enable(1),A.instancingMorph&&o.enable(2),A.matcap&&o.enable(3),A.envMap&&o.enable(4),A.normalMapObjectSpace&&o.enable(5),A.normalMapTangentSpace&&o.enable(6),A.clearcoat&&o.enable(7),A.iridescence&&o.enable(8),A.alphaTest&&o.enable(9),A.vertexColors&&o.enable(10),A.vertexAlphas&&o.enable(11),A.vertexUv1s&&o.enable(12),A.vertexUv2s&&o.enable(13),A.vertexUv3s&&o.enable(14),A.vertexTangents&&o.enable(15),A.anisotropy&&o.enable(16),A.alphaHash&&o.enable(17),A.batching&&o.enable(18),A.dispersion&&o.enable(19),A.retroreflection&&o.enable(24),A.diffuseRoughness&&o.enable(25),A.batchingColor&&o.enable(20),A.gradientMap&&o.enable(21),A.packedNormalMap&&o.enable(22),A.vertexNormals&&o.enable(23),y.push(o.mask),o.disableAll(),A.fog&&o.enable(0),A.useFog&&o.enable(1),A.flatShading&&o.enable(2),A.logarithmicDepthBuffer&&o.enable(3),A.reversedDepthBuffer&&o.enable(4),A.skinning&&o.enable(5),A.morphTargets&&o.enable(6),A.morphNormals&&o.enable(7),A.morphColors&&o.enable(8),A.premultipliedAlpha&&o.enable(9),A.shadowMapEnabled&&o.enable(10),A.doubleSided&&o.enable(11),A.flipSided&&o.enable(12),A.useDepthPacking&&o.enable(13),A.dithering&&o.enable(14),A.transmission&&o.enable(15),A.sheen&&o.enable(16),A.opaque&&o.enable(17),A.pointsUvs&&o.enable(18),A.decodeVideoTexture&&o.enable(19),A.decodeVideoTextureEmissive&&o.enable(20),A.alphaToCoverage&&o.enable(21),A.numLightProbeGrids>0&&o.enable(22),A.hasPositionAttribute&&o.enable(23),y.push(o.mask)}function v(y){let A=f[y.type],k;if(A){let D=Mr[A];k=vb.clone(D.uniforms)}else k=y.uniforms;return k}function T(y,A){let k=u.get(A);return k!==void 0?++k.usedTimes:(k=new PN(n,A,y,r),c.push(k),u.set(A,k)),k}function M(y){if(--y.usedTimes===0){let A=c.indexOf(y);c[A]=c[c.length-1],c.pop(),u.delete(y.cacheKey),y.destroy()}}function R(y){a.remove(y)}function w(){a.dispose()}return{getParameters:p,getProgramCacheKey:x,getUniforms:v,acquireProgram:T,releaseProgram:M,releaseShaderCache:R,programs:c,dispose:w}}function ON(){let n=new WeakMap;function e(o){return n.has(o)}function t(o){let a=n.get(o);return a===void 0&&(a={},n.set(o,a)),a}function i(o){n.delete(o)}function r(o,a,l){n.get(o)[a]=l}function s(){n=new WeakMap}return{has:e,get:t,remove:i,update:r,dispose:s}}function FN(n,e){return n.groupOrder!==e.groupOrder?n.groupOrder-e.groupOrder:n.renderOrder!==e.renderOrder?n.renderOrder-e.renderOrder:n.material.id!==e.material.id?n.material.id-e.material.id:n.materialVariant!==e.materialVariant?n.materialVariant-e.materialVariant:n.z!==e.z?n.z-e.z:n.id-e.id}function Vb(n,e){return n.groupOrder!==e.groupOrder?n.groupOrder-e.groupOrder:n.renderOrder!==e.renderOrder?n.renderOrder-e.renderOrder:n.z!==e.z?e.z-n.z:n.id-e.id}function Gb(){let n=[],e=0,t=[],i=[],r=[];function s(){e=0,t.length=0,i.length=0,r.length=0}function o(f){let d=0;return f.isInstancedMesh&&(d+=2),f.isSkinnedMesh&&(d+=1),d}function a(f,d,p,x,m,g){let v=n[e];return v===void 0?(v={id:f.id,object:f,geometry:d,material:p,materialVariant:o(f),groupOrder:x,renderOrder:f.renderOrder,z:m,group:g},n[e]=v):(v.id=f.id,v.object=f,v.geometry=d,v.material=p,v.materialVariant=o(f),v.groupOrder=x,v.renderOrder=f.renderOrder,v.z=m,v.group=g),e++,v}function l(f,d,p,x,m,g,v){v.reversedDepth===!0&&(m=-m);let T=a(f,d,p,x,m,g);p.transmission>0?i.push(T):p.transparent===!0?r.push(T):t.push(T)}function c(f,d,p,x,m,g){let v=a(f,d,p,x,m,g);p.transmission>0?i.unshift(v):p.transparent===!0?r.unshift(v):t.unshift(v)}function u(f,d){t.length>1&&t.sort(f||FN),i.length>1&&i.sort(d||Vb),r.length>1&&r.sort(d||Vb)}function h(){for(let f=e,d=n.length;f<d;f++){let p=n[f];if(p.id===null)break;p.id=null,p.object=null,p.geometry=null,p.material=null,p.group=null}}return{opaque:t,transmissive:i,transparent:r,init:s,push:l,unshift:c,finish:h,sort:u}}function BN(){let n=new WeakMap;function e(i,r){let s=n.get(i),o;return s===void 0?(o=new Gb,n.set(i,[o])):r>=s.length?(o=new Gb,s.push(o)):o=s[r],o}function t(){n=new WeakMap}return{get:e,dispose:t}}function kN(){let n={};return{get:function(e){if(n[e.id]!==void 0)return n[e.id];let t;switch(e.type){case"SunLight":case"DirectionalLight":t={direction:new Y,color:new ft};break;case"SpotLight":t={position:new Y,direction:new Y,color:new ft,distance:0,coneCos:0,penumbraCos:0,decay:0};break;case"PointLight":t={position:new Y,color:new ft,distance:0,decay:0};break;case"HemisphereLight":t={direction:new Y,skyColor:new ft,groundColor:new ft};break;case"RectAreaLight":t={color:new ft,position:new Y,halfWidth:new Y,halfHeight:new Y};break}return n[e.id]=t,t}}}function VN(){let n={};return{get:function(e){if(n[e.id]!==void 0)return n[e.id];let t;switch(e.type){case"SunLight":case"DirectionalLight":t={shadowIntensity:1,shadowBias:0,shadowNormalBias:0,shadowRadius:1,shadowMapSize:new it};break;case"SpotLight":t={shadowIntensity:1,shadowBias:0,shadowNormalBias:0,shadowRadius:1,shadowMapSize:new it};break;case"PointLight":t={shadowIntensity:1,shadowBias:0,shadowNormalBias:0,shadowRadius:1,shadowMapSize:new it,shadowCameraNear:1,shadowCameraFar:1e3};break}return n[e.id]=t,t}}}var GN=0;function zN(n,e){return(e.castShadow?2:0)-(n.castShadow?2:0)+(e.map?1:0)-(n.map?1:0)}function HN(n){let e=new kN,t=VN(),i={version:0,hash:{sunLength:-1,directionalLength:-1,pointLength:-1,spotLength:-1,rectAreaLength:-1,hemiLength:-1,numSunShadows:-1,numDirectionalShadows:-1,numPointShadows:-1,numSpotShadows:-1,numSpotMaps:-1,numLightProbes:-1},ambient:[0,0,0],probe:[],sun:[],sunShadow:[],sunShadowMap:[],sunShadowMatrix:[],sunShadowCascade:[],directional:[],directionalShadow:[],directionalShadowMap:[],directionalShadowMatrix:[],spot:[],spotLightMap:[],spotShadow:[],spotShadowMap:[],spotLightMatrix:[],rectArea:[],rectAreaLTC1:null,rectAreaLTC2:null,point:[],pointShadow:[],pointShadowMap:[],pointShadowMatrix:[],hemi:[],numSpotLightShadowsWithMaps:0,numLightProbes:0};for(let c=0;c<9;c++)i.probe.push(new Y);let r=new Y,s=new Ht,o=new Ht;function a(c){let u=0,h=0,f=0;for(let H=0;H<9;H++)i.probe[H].set(0,0,0);let d=0,p=0,x=0,m=0,g=0,v=0,T=0,M=0,R=0,w=0,y=0,A=0,k=0,D=0;c.sort(zN);for(let H=0,z=c.length;H<z;H++){let N=c[H],F=N.color,Z=N.intensity,V=N.distance,le=null;if(N.shadow&&N.shadow.map&&(N.shadow.map.texture.format===bs?le=N.shadow.map.texture:le=N.shadow.map.depthTexture||N.shadow.map.texture),N.isAmbientLight)u+=F.r*Z,h+=F.g*Z,f+=F.b*Z;else if(N.isLightProbe){for(let q=0;q<9;q++)i.probe[q].addScaledVector(N.sh.coefficients[q],Z);D++}else if(N.isSunLight){let q=e.get(N);if(q.color.copy(N.color).multiplyScalar(N.intensity),N.castShadow){let Q=N.shadow,ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize.copy(Q.mapSize).multiply(Q.getFrameExtents()),i.sunShadow[p]=ie,i.sunShadowMap[p]=le;let fe=Q.getViewportCount();for(let he=0;he<fe;he++)i.sunShadowMatrix[x+he]=Q.getMatrix(he),i.sunShadowCascade[x+he]=Q._cascadeData[he];x+=fe,p++}i.sun[d]=q,d++}else if(N.isDirectionalLight){let q=e.get(N);if(q.color.copy(N.color).multiplyScalar(N.intensity),N.castShadow){let Q=N.shadow,ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize=Q.mapSize,i.directionalShadow[m]=ie,i.directionalShadowMap[m]=le,i.directionalShadowMatrix[m]=N.shadow.matrix,R++}i.directional[m]=q,m++}else if(N.isSpotLight){let q=e.get(N);q.position.setFromMatrixPosition(N.matrixWorld),q.color.copy(F).multiplyScalar(Z),q.distance=V,q.coneCos=Math.cos(N.angle),q.penumbraCos=Math.cos(N.angle*(1-N.penumbra)),q.decay=N.decay,i.spot[v]=q;let Q=N.shadow;if(N.map&&(i.spotLightMap[A]=N.map,A++,Q.updateMatrices(N),N.castShadow&&k++),i.spotLightMatrix[v]=Q.matrix,N.castShadow){let ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize=Q.mapSize,i.spotShadow[v]=ie,i.spotShadowMap[v]=le,y++}v++}else if(N.isRectAreaLight){let q=e.get(N);q.color.copy(F).multiplyScalar(Z),q.halfWidth.set(N.width*.5,0,0),q.halfHeight.set(0,N.height*.5,0),i.rectArea[T]=q,T++}else if(N.isPointLight){let q=e.get(N);if(q.color.copy(N.color).multiplyScalar(N.intensity),q.distance=N.distance,q.decay=N.decay,N.castShadow){let Q=N.shadow,ie=t.get(N);ie.shadowIntensity=Q.intensity,ie.shadowBias=Q.bias,ie.shadowNormalBias=Q.normalBias,ie.shadowRadius=Q.radius,ie.shadowMapSize=Q.mapSize,ie.shadowCameraNear=Q.camera.near,ie.shadowCameraFar=Q.camera.far,i.pointShadow[g]=ie,i.pointShadowMap[g]=le,i.pointShadowMatrix[g]=N.shadow.matrix,w++}i.point[g]=q,g++}else if(N.isHemisphereLight){let q=e.get(N);q.skyColor.copy(N.color).multiplyScalar(Z),q.groundColor.copy(N.groundColor).multiplyScalar(Z),i.hemi[M]=q,M++}}T>0&&(n.has("OES_texture_float_linear")===!0?(i.rectAreaLTC1=Le.LTC_FLOAT_1,i.rectAreaLTC2=Le.LTC_FLOAT_2):(i.rectAreaLTC1=Le.LTC_HALF_1,i.rectAreaLTC2=Le.LTC_HALF_2)),i.ambient[0]=u,i.ambient[1]=h,i.ambient[2]=f;let L=i.hash;(L.sunLength!==d||L.directionalLength!==m||L.pointLength!==g||L.spotLength!==v||L.rectAreaLength!==T||L.hemiLength!==M||L.numSunShadows!==p||L.numDirectionalShadows!==R||L.numPointShadows!==w||L.numSpotShadows!==y||L.numSpotMaps!==A||L.numLightProbes!==D)&&(i.sun.length=d,i.directional.length=m,i.spot.length=v,i.rectArea.length=T,i.point.length=g,i.hemi.length=M,i.sunShadow.length=p,i.sunShadowMap.length=p,i.sunShadowMatrix.length=x,i.sunShadowCascade.length=x,i.directionalShadow.length=R,i.directionalShadowMap.length=R,i.directionalShadowMatrix.length=R,i.pointShadow.length=w,i.pointShadowMap.length=w,i.pointShadowMatrix.length=w,i.spotShadow.length=y,i.spotShadowMap.length=y,i.spotLightMatrix.length=y+A-k,i.spotLightMap.length=A,i.numSpotLightShadowsWithMaps=k,i.numLightProbes=D,L.sunLength=d,L.directionalLength=m,L.pointLength=g,L.spotLength=v,L.rectAreaLength=T,L.hemiLength=M,L.numSunShadows=p,L.numDirectionalShadows=R,L.numPointShadows=w,L.numSpotShadows=y,L.numSpotMaps=A,L.numLightProbes=D,i.version=GN++)}function l(c,u){let h=0,f=0,d=0,p=0,x=0,m=0,g=u.matrixWorldInverse;for(let v=0,T=c.length;v<T;v++){let M=c[v];if(M.isSunLight){let R=i.sun[h];R.direction.setFromMatrixPosition(M.matrixWorld),R.direction.transformDirection(g),h++}else if(M.isDirectionalLight){let R=i.directional[f];R.direction.setFromMatrixPosition(M.matrixWorld),r.setFromMatrixPosition(M.target.matrixWorld),R.direction.sub(r),R.direction.transformDirection(g),f++}else if(M.isSpotLight){let R=i.spot[p];R.position.setFromMatrixPosition(M.matrixWorld),R.position.applyMatrix4(g),R.direction.setFromMatrixPosition(M.matrixWorld),r.setFromMatrixPosition(M.target.matrixWorld),R.direction.sub(r),R.direction.transformDirection(g),p++}else if(M.isRectAreaLight){let R=i.rectArea[x];R.position.setFromMatrixPosition(M.matrixWorld),R.position.applyMatrix4(g),o.identity(),s.copy(M.matrixWorld),s.premultiply(g),o.extractRotation(s),R.halfWidth.set(M.width*.5,0,0),R.halfHeight.set(0,M.height*.5,0),R.halfWidth.applyMatrix4(o),R.halfHeight.applyMatrix4(o),x++}else if(M.isPointLight){let R=i.point[d];R.position.setFromMatrixPosition(M.matrixWorld),R.position.applyMatrix4(g),d++}else if(M.isHemisphereLight){let R=i.hemi[m];R.direction.setFromMatrixPosition(M.matrixWorld),R.direction.transformDirection(g),m++}}}return{setup:a,setupView:l,state:i}}function zb(n){let e=new HN(n),t=[],i=[],r=[];function s(h){u.camera=h,t.length=0,i.length=0,r.length=0}function o(h){h.isLightProbeGrid?r.push(h):t.push(h)}function a(h){i.push(h)}function l(){e.setup(t),r.sort((h,f)=>h.priority-f.priority||h.id-f.id)}function c(h){e.setupView(t,h)}let u={lightsArray:t,shadowsArray:i,lightProbeGridArray:r,camera:null,lights:e,transmissionRenderTarget:{},textureUnits:0};return{init:s,state:u,setupLights:l,setupLightsView:c,pushLight:o,pushShadow:a}}function WN(n){let e=new WeakMap;function t(r,s=0){let o=e.get(r),a;return o===void 0?(a=new zb(n),e.set(r,[a])):s>=o.length?(a=new zb(n),o.push(a)):a=o[s],a}function i(){e=new WeakMap}return{get:t,dispose:i}}var XN=`void main() {
	gl_Position = vec4( position, 1.0 );
}`,YN=`uniform sampler2D shadow_pass;
uniform vec2 resolution;
uniform float radius;
void main() {
	const float samples = float( VSM_SAMPLES );
	float mean = 0.0;
	float squared_mean = 0.0;
	float uvStride = samples <= 1.0 ? 0.0 : 2.0 / ( samples - 1.0 );
	float uvStart = samples <= 1.0 ? 0.0 : - 1.0;
	for ( float i = 0.0; i < samples; i ++ ) {
		float uvOffset = uvStart + i * uvStride;
		#ifdef HORIZONTAL_PASS
			vec2 distribution = texture2D( shadow_pass, ( gl_FragCoord.xy + vec2( uvOffset, 0.0 ) * radius ) / resolution ).rg;
			mean += distribution.x;
			squared_mean += distribution.y * distribution.y + distribution.x * distribution.x;
		#else
			float depth = texture2D( shadow_pass, ( gl_FragCoord.xy + vec2( 0.0, uvOffset ) * radius ) / resolution ).r;
			mean += depth;
			squared_mean += depth * depth;
		#endif
	}
	mean = mean / samples;
	squared_mean = squared_mean / samples;
	float std_dev = sqrt( max( 0.0, squared_mean - mean * mean ) );
	gl_FragColor = vec4( mean, std_dev, 0.0, 1.0 );
}`,ZN=[new Y(1,0,0),new Y(-1,0,0),new Y(0,1,0),new Y(0,-1,0),new Y(0,0,1),new Y(0,0,-1)],KN=[new Y(0,-1,0),new Y(0,-1,0),new Y(0,0,1),new Y(0,0,-1),new Y(0,-1,0),new Y(0,-1,0)],Hb=new Ht,zl=new Y,Bm=new Y;function $N(n,e,t){let i=new ps,r=new it,s=new it,o=new jt,a=new rh,l=new sh,c={},u=t.maxTextureSize,h={[vs]:ui,[ui]:vs,[Fi]:Fi},f=new vr({defines:{VSM_SAMPLES:8},uniforms:{shadow_pass:{value:null},resolution:{value:new it},radius:{value:4}},vertexShader:XN,fragmentShader:YN}),d=f.clone();d.defines.HORIZONTAL_PASS=1;let p=new ci;p.setAttribute("position",new $n(new Float32Array([-1,-1,.5,3,-1,.5,-1,3,.5]),3));let x=new Ti(p,f),m=this;this.enabled=!1,this.autoUpdate=!0,this.needsUpdate=!1,this.type=Dl;let g=this.type;this.render=function(w,y,A){if(m.enabled===!1||m.autoUpdate===!1&&m.needsUpdate===!1||w.length===0)return;this.type===Ov&&(Ke("WebGLShadowMap: PCFSoftShadowMap has been removed. Using PCFShadowMap instead."),this.type=Dl);let k=n.getRenderTarget(),D=n.getActiveCubeFace(),L=n.getActiveMipmapLevel(),H=n.state;H.setBlending(Ys),H.buffers.depth.getReversed()===!0?H.buffers.color.setClear(0,0,0,0):H.buffers.color.setClear(1,1,1,1),H.buffers.depth.setTest(!0),H.setScissorTest(!1);let z=g!==this.type;z&&y.traverse(function(N){N.material&&(Array.isArray(N.material)?N.material.forEach(F=>F.needsUpdate=!0):N.material.needsUpdate=!0)});for(let N=0,F=w.length;N<F;N++){let Z=w[N],V=Z.shadow;if(V===void 0){Ke("WebGLShadowMap:",Z,"has no shadow.");continue}if(V.autoUpdate===!1&&V.needsUpdate===!1)continue;r.copy(V.mapSize);let le=V.getFrameExtents();r.multiply(le),s.copy(V.mapSize),(r.x>u||r.y>u)&&(r.x>u&&(s.x=Math.floor(u/le.x),r.x=s.x*le.x,V.mapSize.x=s.x),r.y>u&&(s.y=Math.floor(u/le.y),r.y=s.y*le.y,V.mapSize.y=s.y));let q=n.state.buffers.depth.getReversed();if(V.camera._reversedDepth=q,V.map===null||z===!0){if(V.map!==null&&(V.map.depthTexture!==null&&(V.map.depthTexture.dispose(),V.map.depthTexture=null),V.map.dispose()),this.type===aa){if(Z.isPointLight){Ke("WebGLShadowMap: VSM shadow maps are not supported for PointLights. Use PCF or BasicShadowMap instead.");continue}V.map=new Ai(r.x,r.y,{format:bs,type:tr,minFilter:li,magFilter:li,generateMipmaps:!1}),V.map.texture.name=Z.name+".shadowMap",V.map.depthTexture=new Wr(r.x,r.y,er),V.map.depthTexture.name=Z.name+".shadowMapDepth",V.map.depthTexture.format=zr,V.map.depthTexture.compareFunction=null,V.map.depthTexture.minFilter=kn,V.map.depthTexture.magFilter=kn}else Z.isPointLight?(V.map=new Wl(r.x),V.map.depthTexture=new El(r.x,Qi)):(V.map=new Ai(r.x,r.y),V.map.depthTexture=new Wr(r.x,r.y,Qi)),V.map.depthTexture.name=Z.name+".shadowMap",V.map.depthTexture.format=zr,this.type===Dl?(V.map.depthTexture.compareFunction=q?wm:Em,V.map.depthTexture.minFilter=li,V.map.depthTexture.magFilter=li):(V.map.depthTexture.compareFunction=null,V.map.depthTexture.minFilter=kn,V.map.depthTexture.magFilter=kn);V.camera.updateProjectionMatrix()}V.map.isWebGLCubeRenderTarget!==!0&&(V.map.width!==r.x||V.map.height!==r.y)&&V.map.setSize(r.x,r.y);let Q=V.map.isWebGLCubeRenderTarget?6:V.getViewportCount();Z.isPointLight!==!0&&V.updateMatrices(Z,A);let ie=(V.camera.layers.mask&4294967294)!==0?V.camera.layers:A.layers;for(let fe=0;fe<Q;fe++){let he=V.getCamera(fe);if(Z.isPointLight){let ee=V.camera,ge=V.matrix,ye=Z.distance||ee.far;ye!==ee.far&&(ee.far=ye,ee.updateProjectionMatrix()),zl.setFromMatrixPosition(Z.matrixWorld),ee.position.copy(zl),Bm.copy(ee.position),Bm.add(ZN[fe]),ee.up.copy(KN[fe]),ee.lookAt(Bm),ee.updateMatrixWorld(),ge.makeTranslation(-zl.x,-zl.y,-zl.z),Hb.multiplyMatrices(ee.projectionMatrix,ee.matrixWorldInverse),V._frustum.setFromProjectionMatrix(Hb,ee.coordinateSystem,ee.reversedDepth)}if(V.map.isWebGLCubeRenderTarget)n.setRenderTarget(V.map,fe),n.clear();else{fe===0&&(n.setRenderTarget(V.map),n.clear());let ee=V.getViewport(fe);o.set(s.x*ee.x,s.y*ee.y,s.x*ee.z,s.y*ee.w),H.viewport(o)}i=V.getFrustum(fe),M(y,A,he,Z,ie,this.type)}V.isPointLightShadow!==!0&&this.type===aa&&v(V,A),V.needsUpdate=!1}g=this.type,m.needsUpdate=!1,n.setRenderTarget(k,D,L)};function v(w,y){let A=e.update(x);f.defines.VSM_SAMPLES!==w.blurSamples&&(f.defines.VSM_SAMPLES=w.blurSamples,d.defines.VSM_SAMPLES=w.blurSamples,f.needsUpdate=!0,d.needsUpdate=!0),w.mapPass===null?w.mapPass=new Ai(r.x,r.y,{format:bs,type:tr}):(w.mapPass.width!==w.map.width||w.mapPass.height!==w.map.height)&&w.mapPass.setSize(w.map.width,w.map.height),f.uniforms.shadow_pass.value=w.map.depthTexture,f.uniforms.resolution.value.set(w.map.width,w.map.height),f.uniforms.radius.value=w.radius,n.setRenderTarget(w.mapPass),n.clear(),n.renderBufferDirect(y,null,A,f,x,null),d.uniforms.shadow_pass.value=w.mapPass.texture,d.uniforms.resolution.value.set(w.map.width,w.map.height),d.uniforms.radius.value=w.radius,n.setRenderTarget(w.map),n.clear(),n.renderBufferDirect(y,null,A,d,x,null)}function T(w,y,A,k){let D=null,L=A.isPointLight===!0?w.customDistanceMaterial:w.customDepthMaterial;if(L!==void 0)D=L;else if(D=A.isPointLight===!0?l:a,n.localClippingEnabled&&y.clipShadows===!0&&Array.isArray(y.clippingPlanes)&&y.clippingPlanes.length!==0||y.displacementMap&&y.displacementScale!==0||y.alphaMap&&y.alphaTest>0||y.map&&y.alphaTest>0||y.alphaToCoverage===!0){let H=D.uuid,z=y.uuid,N=c[H];N===void 0&&(N={},c[H]=N);let F=N[z];F===void 0&&(F=D.clone(),N[z]=F,y.addEventListener("dispose",R)),D=F}if(D.visible=y.visible,D.wireframe=y.wireframe,k===aa?D.side=y.shadowSide!==null?y.shadowSide:y.side:D.side=y.shadowSide!==null?y.shadowSide:h[y.side],D.alphaMap=y.alphaMap,D.alphaTest=y.alphaToCoverage===!0?.5:y.alphaTest,D.map=y.map,D.clipShadows=y.clipShadows,D.clippingPlanes=y.clippingPlanes,D.clipIntersection=y.clipIntersection,D.displacementMap=y.displacementMap,D.displacementScale=y.displacementScale,D.displacementBias=y.displacementBias,D.wireframeLinewidth=y.wireframeLinewidth,D.linewidth=y.linewidth,A.isPointLight===!0&&D.isMeshDistanceMaterial===!0){let H=n.properties.get(D);H.light=A}return D}function M(w,y,A,k,D,L){if(w.visible===!1)return;if(w.layers.test(D)&&(w.isMesh||w.isLine||w.isPoints)&&(w.castShadow||w.receiveShadow&&L===aa)&&(!w.frustumCulled||w.intersectsFrustum(i))){w.modelViewMatrix.multiplyMatrices(A.matrixWorldInverse,w.matrixWorld);let N=e.update(w),F=w.material;if(Array.isArray(F)){let Z=N.groups;for(let V=0,le=Z.length;V<le;V++){let q=Z[V],Q=F[q.materialIndex];if(Q&&Q.visible){let ie=T(w,Q,k,L);w.onBeforeShadow(n,w,y,A,N,ie,q),n.renderBufferDirect(A,null,N,ie,w,q),w.onAfterShadow(n,w,y,A,N,ie,q)}}}else if(F.visible){let Z=T(w,F,k,L);w.onBeforeShadow(n,w,y,A,N,Z,null),n.renderBufferDirect(A,null,N,Z,w,null),w.onAfterShadow(n,w,y,A,N,Z,null)}}let z=w.children;for(let N=0,F=z.length;N<F;N++)M(z[N],y,A,k,D,L)}function R(w){w.target.removeEventListener("dispose",R);for(let A in c){let k=c[A],D=w.target.uuid;D in k&&(k[D].dispose(),delete k[D])}}}function qN(n,e){function t(){let U=!1,se=new jt,ne=null,Ae=new jt(0,0,0,0);return{setMask:function(ve){ne!==ve&&!U&&(n.colorMask(ve,ve,ve,ve),ne=ve)},setLocked:function(ve){U=ve},setClear:function(ve,Ee,We,je,ce){ce===!0&&(ve*=je,Ee*=je,We*=je),se.set(ve,Ee,We,je),Ae.equals(se)===!1&&(n.clearColor(ve,Ee,We,je),Ae.copy(se))},reset:function(){U=!1,ne=null,Ae.set(-1,0,0,0)}}}function i(){let U=!1,se=!1,ne=null,Ae=null,ve=null;return{setReversed:function(Ee){if(se!==Ee){let We=e.get("EXT_clip_control");Ee?We.clipControlEXT(We.LOWER_LEFT_EXT,We.ZERO_TO_ONE_EXT):We.clipControlEXT(We.LOWER_LEFT_EXT,We.NEGATIVE_ONE_TO_ONE_EXT),se=Ee;let je=ve;ve=null,this.setClear(je)}},getReversed:function(){return se},setTest:function(Ee){Ee?_e(n.DEPTH_TEST):ze(n.DEPTH_TEST)},setMask:function(Ee){ne!==Ee&&!U&&(n.depthMask(Ee),ne=Ee)},setFunc:function(Ee){if(se&&(Ee=gb[Ee]),Ae!==Ee){switch(Ee){case ku:n.depthFunc(n.NEVER);break;case Vu:n.depthFunc(n.ALWAYS);break;case Gu:n.depthFunc(n.LESS);break;case Ko:n.depthFunc(n.LEQUAL);break;case zu:n.depthFunc(n.EQUAL);break;case Hu:n.depthFunc(n.GEQUAL);break;case Wu:n.depthFunc(n.GREATER);break;case Xu:n.depthFunc(n.NOTEQUAL);break;default:n.depthFunc(n.LEQUAL)}Ae=Ee}},setLocked:function(Ee){U=Ee},setClear:function(Ee){ve!==Ee&&(ve=Ee,se&&(Ee=1-Ee),n.clearDepth(Ee))},reset:function(){U=!1,ne=null,Ae=null,ve=null,se=!1}}}function r(){let U=!1,se=null,ne=null,Ae=null,ve=null,Ee=null,We=null,je=null,ce=null;return{setTest:function(ke){U||(ke?_e(n.STENCIL_TEST):ze(n.STENCIL_TEST))},setMask:function(ke){se!==ke&&!U&&(n.stencilMask(ke),se=ke)},setFunc:function(ke,Qe,Ie){(ne!==ke||Ae!==Qe||ve!==Ie)&&(n.stencilFunc(ke,Qe,Ie),ne=ke,Ae=Qe,ve=Ie)},setOp:function(ke,Qe,Ie){(Ee!==ke||We!==Qe||je!==Ie)&&(n.stencilOp(ke,Qe,Ie),Ee=ke,We=Qe,je=Ie)},setLocked:function(ke){U=ke},setClear:function(ke){ce!==ke&&(n.clearStencil(ke),ce=ke)},reset:function(){U=!1,se=null,ne=null,Ae=null,ve=null,Ee=null,We=null,je=null,ce=null}}}let s=new t,o=new i,a=new r,l={},c=new WeakMap,u={},h={},f={},d=new WeakMap,p=[],x=null,m=!1,g=null,v=null,T=null,M=null,R=null,w=null,y=null,A=new ft(0,0,0),k=0,D=!1,L=null,H=null,z=null,N=null,F=null,Z=n.getParameter(n.MAX_COMBINED_TEXTURE_IMAGE_UNITS),V=!1,le=0,q=n.getParameter(n.VERSION);q.indexOf("WebGL")!==-1?(le=parseFloat(/^WebGL (\d)/.exec(q)[1]),V=le>=1):q.indexOf("OpenGL ES")!==-1&&(le=parseFloat(/^OpenGL ES (\d)/.exec(q)[1]),V=le>=2);let Q=null,ie={},fe=n.getParameter(n.SCISSOR_BOX),he=n.getParameter(n.VIEWPORT),ee=new jt().fromArray(fe),ge=new jt().fromArray(he);function ye(U,se,ne,Ae){let ve=new Uint8Array(4),Ee=n.createTexture();n.bindTexture(U,Ee),n.texParameteri(U,n.TEXTURE_MIN_FILTER,n.NEAREST),n.texParameteri(U,n.TEXTURE_MAG_FILTER,n.NEAREST);for(let We=0;We<ne;We++)U===n.TEXTURE_3D||U===n.TEXTURE_2D_ARRAY?n.texImage3D(se,0,n.RGBA,1,1,Ae,0,n.RGBA,n.UNSIGNED_BYTE,ve):n.texImage2D(se+We,0,n.RGBA,1,1,0,n.RGBA,n.UNSIGNED_BYTE,ve);return Ee}let xe={};xe[n.TEXTURE_2D]=ye(n.TEXTURE_2D,n.TEXTURE_2D,1),xe[n.TEXTURE_CUBE_MAP]=ye(n.TEXTURE_CUBE_MAP,n.TEXTURE_CUBE_MAP_POSITIVE_X,6),xe[n.TEXTURE_2D_ARRAY]=ye(n.TEXTURE_2D_ARRAY,n.TEXTURE_2D_ARRAY,1,1),xe[n.TEXTURE_3D]=ye(n.TEXTURE_3D,n.TEXTURE_3D,1,1),s.setClear(0,0,0,1),o.setClear(1),a.setClear(0),_e(n.DEPTH_TEST),o.setFunc(Ko),hn(!1),Ot(im),_e(n.CULL_FACE),qt(Ys);function _e(U){u[U]!==!0&&(n.enable(U),u[U]=!0)}function ze(U){u[U]!==!1&&(n.disable(U),u[U]=!1)}function $e(U,se){return f[U]!==se?(n.bindFramebuffer(U,se),f[U]=se,U===n.DRAW_FRAMEBUFFER&&(f[n.FRAMEBUFFER]=se),U===n.FRAMEBUFFER&&(f[n.DRAW_FRAMEBUFFER]=se),!0):!1}function Fe(U,se){let ne=p,Ae=!1;if(U){ne=d.get(se),ne===void 0&&(ne=[],d.set(se,ne));let ve=U.textures;if(ne.length!==ve.length||ne[0]!==n.COLOR_ATTACHMENT0){for(let Ee=0,We=ve.length;Ee<We;Ee++)ne[Ee]=n.COLOR_ATTACHMENT0+Ee;ne.length=ve.length,Ae=!0}}else ne[0]!==n.BACK&&(ne[0]=n.BACK,Ae=!0);Ae&&n.drawBuffers(ne)}function st(U){return x!==U?(n.useProgram(U),x=U,!0):!1}let ct={[Zs]:n.FUNC_ADD,[Bv]:n.FUNC_SUBTRACT,[kv]:n.FUNC_REVERSE_SUBTRACT};ct[Vv]=n.MIN,ct[Gv]=n.MAX;let ot={[zv]:n.ZERO,[Hv]:n.ONE,[Wv]:n.SRC_COLOR,[am]:n.SRC_ALPHA,[qv]:n.SRC_ALPHA_SATURATE,[Kv]:n.DST_COLOR,[Yv]:n.DST_ALPHA,[Xv]:n.ONE_MINUS_SRC_COLOR,[lm]:n.ONE_MINUS_SRC_ALPHA,[$v]:n.ONE_MINUS_DST_COLOR,[Zv]:n.ONE_MINUS_DST_ALPHA,[Jv]:n.CONSTANT_COLOR,[jv]:n.ONE_MINUS_CONSTANT_COLOR,[Qv]:n.CONSTANT_ALPHA,[eb]:n.ONE_MINUS_CONSTANT_ALPHA};function qt(U,se,ne,Ae,ve,Ee,We,je,ce,ke){if(U===Ys){m===!0&&(ze(n.BLEND),m=!1);return}if(m===!1&&(_e(n.BLEND),m=!0),U!==Fv){if(U!==g||ke!==D){if((v!==Zs||R!==Zs)&&(n.blendEquation(n.FUNC_ADD),v=Zs,R=Zs),ke)switch(U){case la:n.blendFuncSeparate(n.ONE,n.ONE_MINUS_SRC_ALPHA,n.ONE,n.ONE_MINUS_SRC_ALPHA);break;case rm:n.blendFunc(n.ONE,n.ONE);break;case sm:n.blendFuncSeparate(n.ZERO,n.ONE_MINUS_SRC_COLOR,n.ZERO,n.ONE);break;case om:n.blendFuncSeparate(n.DST_COLOR,n.ONE_MINUS_SRC_ALPHA,n.ZERO,n.ONE);break;default:nt("WebGLState: Invalid blending: ",U);break}else switch(U){case la:n.blendFuncSeparate(n.SRC_ALPHA,n.ONE_MINUS_SRC_ALPHA,n.ONE,n.ONE_MINUS_SRC_ALPHA);break;case rm:n.blendFuncSeparate(n.SRC_ALPHA,n.ONE,n.ONE,n.ONE);break;case sm:nt("WebGLState: SubtractiveBlending requires material.premultipliedAlpha = true");break;case om:nt("WebGLState: MultiplyBlending requires material.premultipliedAlpha = true");break;default:nt("WebGLState: Invalid blending: ",U);break}T=null,M=null,w=null,y=null,A.set(0,0,0),k=0,g=U,D=ke}return}ve=ve||se,Ee=Ee||ne,We=We||Ae,(se!==v||ve!==R)&&(n.blendEquationSeparate(ct[se],ct[ve]),v=se,R=ve),(ne!==T||Ae!==M||Ee!==w||We!==y)&&(n.blendFuncSeparate(ot[ne],ot[Ae],ot[Ee],ot[We]),T=ne,M=Ae,w=Ee,y=We),(je.equals(A)===!1||ce!==k)&&(n.blendColor(je.r,je.g,je.b,ce),A.copy(je),k=ce),g=U,D=!1}function Gt(U,se){U.side===Fi?ze(n.CULL_FACE):_e(n.CULL_FACE);let ne=U.side===ui;se&&(ne=!ne),hn(ne),U.blending===la&&U.transparent===!1?qt(Ys):qt(U.blending,U.blendEquation,U.blendSrc,U.blendDst,U.blendEquationAlpha,U.blendSrcAlpha,U.blendDstAlpha,U.blendColor,U.blendAlpha,U.premultipliedAlpha),o.setFunc(U.depthFunc),o.setTest(U.depthTest),o.setMask(U.depthWrite),s.setMask(U.colorWrite);let Ae=U.stencilWrite;a.setTest(Ae),Ae&&(a.setMask(U.stencilWriteMask),a.setFunc(U.stencilFunc,U.stencilRef,U.stencilFuncMask),a.setOp(U.stencilFail,U.stencilZFail,U.stencilZPass)),St(U.polygonOffset,U.polygonOffsetFactor,U.polygonOffsetUnits),U.alphaToCoverage===!0?_e(n.SAMPLE_ALPHA_TO_COVERAGE):ze(n.SAMPLE_ALPHA_TO_COVERAGE)}function hn(U){L!==U&&(U?n.frontFace(n.CW):n.frontFace(n.CCW),L=U)}function Ot(U){U!==Dv?(_e(n.CULL_FACE),U!==H&&(U===im?n.cullFace(n.BACK):U===Uv?n.cullFace(n.FRONT):n.cullFace(n.FRONT_AND_BACK))):ze(n.CULL_FACE),H=U}function Pn(U){U!==z&&(V&&n.lineWidth(U),z=U)}function St(U,se,ne){U?(_e(n.POLYGON_OFFSET_FILL),(N!==se||F!==ne)&&(N=se,F=ne,o.getReversed()&&(se=-se,ne=-ne),n.polygonOffset(se,ne))):ze(n.POLYGON_OFFSET_FILL)}function En(U){U?_e(n.SCISSOR_TEST):ze(n.SCISSOR_TEST)}function tn(U){U===void 0&&(U=n.TEXTURE0+Z-1),Q!==U&&(n.activeTexture(U),Q=U)}function fn(U,se,ne){ne===void 0&&(Q===null?ne=n.TEXTURE0+Z-1:ne=Q);let Ae=ie[ne];Ae===void 0&&(Ae={type:void 0,texture:void 0},ie[ne]=Ae),(Ae.type!==U||Ae.texture!==se)&&(Q!==ne&&(n.activeTexture(ne),Q=ne),n.bindTexture(U,se||xe[U]),Ae.type=U,Ae.texture=se)}function O(){let U=ie[Q];U!==void 0&&U.type!==void 0&&(n.bindTexture(U.type,null),U.type=void 0,U.texture=void 0)}function Ce(){try{n.compressedTexImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function Ze(){try{n.compressedTexImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function lt(){try{n.texSubImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function we(){try{n.texSubImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function Bt(){try{n.compressedTexSubImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function He(){try{n.compressedTexSubImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function Ye(){try{n.texStorage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function I(){try{n.texStorage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function b(){try{n.texImage2D(...arguments)}catch(U){nt("WebGLState:",U)}}function X(){try{n.texImage3D(...arguments)}catch(U){nt("WebGLState:",U)}}function ue(U){return h[U]!==void 0?h[U]:n.getParameter(U)}function oe(U,se){h[U]!==se&&(n.pixelStorei(U,se),h[U]=se)}function be(U){ee.equals(U)===!1&&(n.scissor(U.x,U.y,U.z,U.w),ee.copy(U))}function Se(U){ge.equals(U)===!1&&(n.viewport(U.x,U.y,U.z,U.w),ge.copy(U))}function te(U,se){let ne=c.get(se);ne===void 0&&(ne=new WeakMap,c.set(se,ne));let Ae=ne.get(U);Ae===void 0&&(Ae=n.getUniformBlockIndex(se,U.name),n.uniformBlockBinding(se,Ae,Ae),ne.set(U,Ae))}function re(U,se,ne){let ve=c.get(se).get(U);l[ve]!==ne&&(n.bindBufferBase(n.UNIFORM_BUFFER,ve,ne),l[ve]=ne)}function pe(){n.disable(n.BLEND),n.disable(n.CULL_FACE),n.disable(n.DEPTH_TEST),n.disable(n.POLYGON_OFFSET_FILL),n.disable(n.SCISSOR_TEST),n.disable(n.STENCIL_TEST),n.disable(n.SAMPLE_ALPHA_TO_COVERAGE),n.blendEquation(n.FUNC_ADD),n.blendFunc(n.ONE,n.ZERO),n.blendFuncSeparate(n.ONE,n.ZERO,n.ONE,n.ZERO),n.blendColor(0,0,0,0),n.colorMask(!0,!0,!0,!0),n.clearColor(0,0,0,0),n.depthMask(!0),n.depthFunc(n.LESS),o.setReversed(!1),n.clearDepth(1),n.stencilMask(4294967295),n.stencilFunc(n.ALWAYS,0,4294967295),n.stencilOp(n.KEEP,n.KEEP,n.KEEP),n.clearStencil(0),n.cullFace(n.BACK),n.frontFace(n.CCW),n.polygonOffset(0,0),n.activeTexture(n.TEXTURE0),n.bindFramebuffer(n.FRAMEBUFFER,null),n.bindFramebuffer(n.DRAW_FRAMEBUFFER,null),n.bindFramebuffer(n.READ_FRAMEBUFFER,null),n.useProgram(null),n.lineWidth(1),n.scissor(0,0,n.canvas.width,n.canvas.height),n.viewport(0,0,n.canvas.width,n.canvas.height),n.pixelStorei(n.PACK_ALIGNMENT,4),n.pixelStorei(n.UNPACK_ALIGNMENT,4),n.pixelStorei(n.UNPACK_FLIP_Y_WEBGL,!1),n.pixelStorei(n.UNPACK_PREMULTIPLY_ALPHA_WEBGL,!1),n.pixelStorei(n.UNPACK_COLORSPACE_CONVERSION_WEBGL,n.BROWSER_DEFAULT_WEBGL),n.pixelStorei(n.PACK_ROW_LENGTH,0),n.pixelStorei(n.PACK_SKIP_PIXELS,0),n.pixelStorei(n.PACK_SKIP_ROWS,0),n.pixelStorei(n.UNPACK_ROW_LENGTH,0),n.pixelStorei(n.UNPACK_IMAGE_HEIGHT,0),n.pixelStorei(n.UNPACK_SKIP_PIXELS,0),n.pixelStorei(n.UNPACK_SKIP_ROWS,0),n.pixelStorei(n.UNPACK_SKIP_IMAGES,0),u={},h={},Q=null,ie={},f={},l={},d=new WeakMap,p=[],x=null,m=!1,g=null,v=null,T=null,M=null,R=null,w=null,y=null,A=new ft(0,0,0),k=0,D=!1,L=null,H=null,z=null,N=null,F=null,ee.set(0,0,n.canvas.width,n.canvas.height),ge.set(0,0,n.canvas.width,n.canvas.height),s.reset(),o.reset(),a.reset()}return{buffers:{color:s,depth:o,stencil:a},enable:_e,disable:ze,bindFramebuffer:$e,drawBuffers:Fe,useProgram:st,setBlending:qt,setMaterial:Gt,setFlipSided:hn,setCullFace:Ot,setLineWidth:Pn,setPolygonOffset:St,setScissorTest:En,activeTexture:tn,bindTexture:fn,unbindTexture:O,compressedTexImage2D:Ce,compressedTexImage3D:Ze,texImage2D:b,texImage3D:X,pixelStorei:oe,getParameter:ue,updateUBOMapping:te,uniformBlockBinding:re,texStorage2D:Ye,texStorage3D:I,texSubImage2D:lt,texSubImage3D:we,compressedTexSubImage2D:Bt,compressedTexSubImage3D:He,scissor:be,viewport:Se,reset:pe}}function JN(n,e,t,i,r,s,o){let a=e.has("WEBGL_multisampled_render_to_texture")?e.get("WEBGL_multisampled_render_to_texture"):null,l=typeof navigator>"u"?!1:/OculusBrowser/g.test(navigator.userAgent),c=new it,u=new WeakMap,h=new Set,f,d=new WeakMap,p=new Set,x=new FinalizationRegistry(I=>p.delete(I)),m=!1;try{m=typeof OffscreenCanvas<"u"&&new OffscreenCanvas(1,1).getContext("2d")!==null}catch{}function g(I,b){return m?new OffscreenCanvas(I,b):ml("canvas")}function v(I,b,X){let ue=1,oe=Ye(I);if((oe.width>X||oe.height>X)&&(ue=X/Math.max(oe.width,oe.height)),ue<1)if(typeof HTMLImageElement<"u"&&I instanceof HTMLImageElement||typeof HTMLCanvasElement<"u"&&I instanceof HTMLCanvasElement||typeof ImageBitmap<"u"&&I instanceof ImageBitmap||typeof VideoFrame<"u"&&I instanceof VideoFrame){let be=Math.floor(ue*oe.width),Se=Math.floor(ue*oe.height);f===void 0&&(f=g(be,Se));let te=b?g(be,Se):f;return te.width=be,te.height=Se,te.getContext("2d").drawImage(I,0,0,be,Se),Ke("WebGLRenderer: Texture has been resized from ("+oe.width+"x"+oe.height+") to ("+be+"x"+Se+")."),te}else return"data"in I&&Ke("WebGLRenderer: Image in DataTexture is too big ("+oe.width+"x"+oe.height+")."),I;return I}function T(I){return I.generateMipmaps}function M(I){n.generateMipmap(I)}function R(I){return I.isWebGLCubeRenderTarget?n.TEXTURE_CUBE_MAP:I.isWebGL3DRenderTarget?n.TEXTURE_3D:I.isWebGLArrayRenderTarget||I.isCompressedArrayTexture?n.TEXTURE_2D_ARRAY:n.TEXTURE_2D}function w(I,b,X,ue,oe,be=!1){if(I!==null){if(n[I]!==void 0)return n[I];Ke("WebGLRenderer: Attempt to use non-existing WebGL internal format '"+I+"'")}let Se;ue&&(Se=e.get("EXT_texture_norm16"),Se||Ke("WebGLRenderer: Unable to use normalized textures without EXT_texture_norm16 extension"));let te=b;if(b===n.RED&&(X===n.FLOAT&&(te=n.R32F),X===n.HALF_FLOAT&&(te=n.R16F),X===n.UNSIGNED_BYTE&&(te=n.R8),X===n.UNSIGNED_SHORT&&Se&&(te=Se.R16_EXT),X===n.SHORT&&Se&&(te=Se.R16_SNORM_EXT)),b===n.RED_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.R8UI),X===n.UNSIGNED_SHORT&&(te=n.R16UI),X===n.UNSIGNED_INT&&(te=n.R32UI),X===n.BYTE&&(te=n.R8I),X===n.SHORT&&(te=n.R16I),X===n.INT&&(te=n.R32I)),b===n.RG&&(X===n.FLOAT&&(te=n.RG32F),X===n.HALF_FLOAT&&(te=n.RG16F),X===n.UNSIGNED_BYTE&&(te=n.RG8),X===n.UNSIGNED_SHORT&&Se&&(te=Se.RG16_EXT),X===n.SHORT&&Se&&(te=Se.RG16_SNORM_EXT)),b===n.RG_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.RG8UI),X===n.UNSIGNED_SHORT&&(te=n.RG16UI),X===n.UNSIGNED_INT&&(te=n.RG32UI),X===n.BYTE&&(te=n.RG8I),X===n.SHORT&&(te=n.RG16I),X===n.INT&&(te=n.RG32I)),b===n.RGB_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.RGB8UI),X===n.UNSIGNED_SHORT&&(te=n.RGB16UI),X===n.UNSIGNED_INT&&(te=n.RGB32UI),X===n.BYTE&&(te=n.RGB8I),X===n.SHORT&&(te=n.RGB16I),X===n.INT&&(te=n.RGB32I)),b===n.RGBA_INTEGER&&(X===n.UNSIGNED_BYTE&&(te=n.RGBA8UI),X===n.UNSIGNED_SHORT&&(te=n.RGBA16UI),X===n.UNSIGNED_INT&&(te=n.RGBA32UI),X===n.BYTE&&(te=n.RGBA8I),X===n.SHORT&&(te=n.RGBA16I),X===n.INT&&(te=n.RGBA32I)),b===n.RGB&&(X===n.UNSIGNED_SHORT&&Se&&(te=Se.RGB16_EXT),X===n.SHORT&&Se&&(te=Se.RGB16_SNORM_EXT),X===n.UNSIGNED_INT_5_9_9_9_REV&&(te=n.RGB9_E5),X===n.UNSIGNED_INT_10F_11F_11F_REV&&(te=n.R11F_G11F_B10F)),b===n.RGBA){let re=be?pl:vt.getTransfer(oe);X===n.FLOAT&&(te=n.RGBA32F),X===n.HALF_FLOAT&&(te=n.RGBA16F),X===n.UNSIGNED_BYTE&&(te=re===Nt?n.SRGB8_ALPHA8:n.RGBA8),X===n.UNSIGNED_SHORT&&Se&&(te=Se.RGBA16_EXT),X===n.SHORT&&Se&&(te=Se.RGBA16_SNORM_EXT),X===n.UNSIGNED_SHORT_4_4_4_4&&(te=n.RGBA4),X===n.UNSIGNED_SHORT_5_5_5_1&&(te=n.RGB5_A1)}return(te===n.R16F||te===n.R32F||te===n.RG16F||te===n.RG32F||te===n.RGBA16F||te===n.RGBA32F)&&e.get("EXT_color_buffer_float"),te}function y(I,b){let X;return I?b===null||b===Qi||b===$s?X=n.DEPTH24_STENCIL8:b===er?X=n.DEPTH32F_STENCIL8:b===ua&&(X=n.DEPTH24_STENCIL8,Ke("DepthTexture: 16 bit depth attachment is not supported with stencil. Using 24-bit attachment.")):b===null||b===Qi||b===$s?X=n.DEPTH_COMPONENT24:b===er?X=n.DEPTH_COMPONENT32F:b===ua&&(X=n.DEPTH_COMPONENT16),X}function A(I,b){return T(I)===!0||I.isFramebufferTexture&&I.minFilter!==kn&&I.minFilter!==li?Math.log2(Math.max(b.width,b.height))+1:I.mipmaps.length>0?I.mipmaps.length:I.isCompressedTexture&&Array.isArray(I.image)?b.mipmaps.length:1}function k(I){let b=new WeakRef(I);i.get(I).__ref=b,p.add(b),x.register(I,b,b)}function D(I){let b=i.get(I).__ref;b!==void 0&&(p.delete(b),x.unregister(b))}function L(I){z(I.target)}function H(I){N(I.target)}function z(I){I.removeEventListener("dispose",L),D(I),Z(I),I.isVideoTexture&&u.delete(I),I.isHTMLTexture&&h.delete(I)}function N(I){I.removeEventListener("dispose",H),D(I),le(I)}function F(){for(let I of p){let b=I.deref();b!==void 0&&(b.isRenderTarget===!0?N(b):z(b))}p.clear(),h.clear()}function Z(I){let b=i.get(I);if(b.__webglInit===void 0)return;let X=I.source,ue=d.get(X);if(ue){let oe=ue[b.__cacheKey];oe.usedTimes--,oe.usedTimes===0&&V(I),Object.keys(ue).length===0&&d.delete(X)}i.remove(I)}function V(I){let b=i.get(I);n.deleteTexture(b.__webglTexture);let X=I.source,ue=d.get(X);delete ue[b.__cacheKey],o.memory.textures--}function le(I){let b=i.get(I);b.__depthDisposeCallback&&b.__depthDisposeCallback();let X=I.depthTexture;if(X&&X.renderTarget===I&&z(X),I.isWebGLCubeRenderTarget)for(let oe=0;oe<6;oe++){if(Array.isArray(b.__webglFramebuffer[oe]))for(let be=0;be<b.__webglFramebuffer[oe].length;be++)n.deleteFramebuffer(b.__webglFramebuffer[oe][be]);else n.deleteFramebuffer(b.__webglFramebuffer[oe]);b.__webglDepthbuffer&&n.deleteRenderbuffer(b.__webglDepthbuffer[oe])}else{if(Array.isArray(b.__webglFramebuffer))for(let oe=0;oe<b.__webglFramebuffer.length;oe++)n.deleteFramebuffer(b.__webglFramebuffer[oe]);else n.deleteFramebuffer(b.__webglFramebuffer);if(b.__webglDepthbuffer&&n.deleteRenderbuffer(b.__webglDepthbuffer),b.__webglMultisampledFramebuffer&&n.deleteFramebuffer(b.__webglMultisampledFramebuffer),b.__webglColorRenderbuffer)for(let oe=0;oe<b.__webglColorRenderbuffer.length;oe++)b.__webglColorRenderbuffer[oe]&&n.deleteRenderbuffer(b.__webglColorRenderbuffer[oe]);b.__webglDepthRenderbuffer&&n.deleteRenderbuffer(b.__webglDepthRenderbuffer)}let ue=I.textures;for(let oe=0,be=ue.length;oe<be;oe++){let Se=i.get(ue[oe]);Se.__webglTexture&&(n.deleteTexture(Se.__webglTexture),o.memory.textures--),i.remove(ue[oe])}i.remove(I)}let q=0;function Q(){q=0}function ie(){return q}function fe(I){q=I}function he(){let I=q;return I>=r.maxTextures&&Ke("WebGLTextures: Trying to use "+(I+1)+" texture units while this GPU supports only "+r.maxTextures),q+=1,I}function ee(I){let b=[];return b.push(I.wrapS),b.push(I.wrapT),b.push(I.wrapR||0),b.push(I.magFilter),b.push(I.minFilter),b.push(I.anisotropy),b.push(I.internalFormat),b.push(I.format),b.push(I.type),b.push(I.generateMipmaps),b.push(I.mipmapsAutoUpdate),b.push(I.premultiplyAlpha),b.push(I.flipY),b.push(I.unpackAlignment),b.push(I.colorSpace),b.join()}function ge(I,b){let X=i.get(I);if(I.isVideoTexture&&Bt(I),I.isRenderTargetTexture===!1&&I.isExternalTexture!==!0&&I.version>0&&X.__version!==I.version){let ue=I.image;if(ue===null)Ke("WebGLRenderer: Texture marked for update but no image data found.");else if(ue.complete===!1)Ke("WebGLRenderer: Texture marked for update but image is incomplete");else{Gt(X,I,b);return}}else I.isExternalTexture&&(X.__webglTexture=I.sourceTexture?I.sourceTexture:null);t.bindTexture(n.TEXTURE_2D,X.__webglTexture,n.TEXTURE0+b)}function ye(I,b){let X=i.get(I);if(I.isRenderTargetTexture===!1&&I.version>0&&X.__version!==I.version){Gt(X,I,b);return}else I.isExternalTexture&&(X.__webglTexture=I.sourceTexture?I.sourceTexture:null);t.bindTexture(n.TEXTURE_2D_ARRAY,X.__webglTexture,n.TEXTURE0+b)}function xe(I,b){let X=i.get(I);if(I.isRenderTargetTexture===!1&&I.version>0&&X.__version!==I.version){Gt(X,I,b);return}t.bindTexture(n.TEXTURE_3D,X.__webglTexture,n.TEXTURE0+b)}function _e(I,b){let X=i.get(I);if(I.version>0&&X.__version!==I.version){hn(X,I,b);return}t.bindTexture(n.TEXTURE_CUBE_MAP,X.__webglTexture,n.TEXTURE0+b)}let ze={[Yu]:n.REPEAT,[yr]:n.CLAMP_TO_EDGE,[Zu]:n.MIRRORED_REPEAT},$e={[kn]:n.NEAREST,[ib]:n.NEAREST_MIPMAP_NEAREST,[Ul]:n.NEAREST_MIPMAP_LINEAR,[li]:n.LINEAR,[bh]:n.LINEAR_MIPMAP_NEAREST,[Xr]:n.LINEAR_MIPMAP_LINEAR},Fe={[ab]:n.NEVER,[Am]:n.ALWAYS,[lb]:n.LESS,[Em]:n.LEQUAL,[cb]:n.EQUAL,[wm]:n.GEQUAL,[ub]:n.GREATER,[hb]:n.NOTEQUAL};function st(I,b){if(b.type===er&&e.has("OES_texture_float_linear")===!1&&(b.magFilter===li||b.magFilter===bh||b.magFilter===Ul||b.magFilter===Xr||b.minFilter===li||b.minFilter===bh||b.minFilter===Ul||b.minFilter===Xr)&&Ke("WebGLRenderer: Unable to use linear filtering with floating point textures. OES_texture_float_linear not supported on this device."),n.texParameteri(I,n.TEXTURE_WRAP_S,ze[b.wrapS]),n.texParameteri(I,n.TEXTURE_WRAP_T,ze[b.wrapT]),(I===n.TEXTURE_3D||I===n.TEXTURE_2D_ARRAY)&&n.texParameteri(I,n.TEXTURE_WRAP_R,ze[b.wrapR]),n.texParameteri(I,n.TEXTURE_MAG_FILTER,$e[b.magFilter]),n.texParameteri(I,n.TEXTURE_MIN_FILTER,$e[b.minFilter]),b.compareFunction&&(n.texParameteri(I,n.TEXTURE_COMPARE_MODE,n.COMPARE_REF_TO_TEXTURE),n.texParameteri(I,n.TEXTURE_COMPARE_FUNC,Fe[b.compareFunction])),e.has("EXT_texture_filter_anisotropic")===!0){if(b.magFilter===kn||b.minFilter!==Ul&&b.minFilter!==Xr||b.type===er&&e.has("OES_texture_float_linear")===!1)return;if(b.anisotropy>1||i.get(b).__currentAnisotropy){let X=e.get("EXT_texture_filter_anisotropic");n.texParameterf(I,X.TEXTURE_MAX_ANISOTROPY_EXT,Math.min(b.anisotropy,r.getMaxAnisotropy())),i.get(b).__currentAnisotropy=b.anisotropy}}}function ct(I,b){let X=!1;I.__webglInit===void 0&&(I.__webglInit=!0,b.addEventListener("dispose",L),k(b));let ue=b.source,oe=d.get(ue);oe===void 0&&(oe={},d.set(ue,oe));let be=ee(b);if(be!==I.__cacheKey){oe[be]===void 0&&(oe[be]={texture:n.createTexture(),usedTimes:0},o.memory.textures++,X=!0),oe[be].usedTimes++;let Se=oe[I.__cacheKey];Se!==void 0&&(oe[I.__cacheKey].usedTimes--,Se.usedTimes===0&&V(b)),I.__cacheKey=be,I.__webglTexture=oe[be].texture}return X}function ot(I,b,X){return Math.floor(Math.floor(I/X)/b)}function qt(I,b,X,ue){let be=I.updateRanges;if(be.length===0)t.texSubImage2D(n.TEXTURE_2D,0,0,0,b.width,b.height,X,ue,b.data);else{be.sort((U,se)=>U.start-se.start);let Se=0;for(let U=1;U<be.length;U++){let se=be[Se],ne=be[U],Ae=se.start+se.count,ve=ot(ne.start,b.width,4),Ee=ot(se.start,b.width,4);ne.start<=Ae+1&&ve===Ee&&ot(ne.start+ne.count-1,b.width,4)===ve?se.count=Math.max(se.count,ne.start+ne.count-se.start):(++Se,be[Se]=ne)}be.length=Se+1;let te=t.getParameter(n.UNPACK_ROW_LENGTH),re=t.getParameter(n.UNPACK_SKIP_PIXELS),pe=t.getParameter(n.UNPACK_SKIP_ROWS);t.pixelStorei(n.UNPACK_ROW_LENGTH,b.width);for(let U=0,se=be.length;U<se;U++){let ne=be[U],Ae=Math.floor(ne.start/4),ve=Math.ceil(ne.count/4),Ee=Ae%b.width,We=Math.floor(Ae/b.width),je=ve,ce=1;t.pixelStorei(n.UNPACK_SKIP_PIXELS,Ee),t.pixelStorei(n.UNPACK_SKIP_ROWS,We),t.texSubImage2D(n.TEXTURE_2D,0,Ee,We,je,ce,X,ue,b.data)}I.clearUpdateRanges(),t.pixelStorei(n.UNPACK_ROW_LENGTH,te),t.pixelStorei(n.UNPACK_SKIP_PIXELS,re),t.pixelStorei(n.UNPACK_SKIP_ROWS,pe)}}function Gt(I,b,X){let ue=n.TEXTURE_2D;(b.isDataArrayTexture||b.isCompressedArrayTexture)&&(ue=n.TEXTURE_2D_ARRAY),b.isData3DTexture&&(ue=n.TEXTURE_3D);let oe=ct(I,b),be=b.source;t.bindTexture(ue,I.__webglTexture,n.TEXTURE0+X);let Se=i.get(be);if(be.version!==Se.__version||oe===!0){if(t.activeTexture(n.TEXTURE0+X),(typeof ImageBitmap<"u"&&b.image instanceof ImageBitmap)===!1){let ce=vt.getPrimaries(vt.workingColorSpace),ke=b.colorSpace===Zr?null:vt.getPrimaries(b.colorSpace),Qe=b.colorSpace===Zr||ce===ke?n.NONE:n.BROWSER_DEFAULT_WEBGL;t.pixelStorei(n.UNPACK_FLIP_Y_WEBGL,b.flipY),t.pixelStorei(n.UNPACK_PREMULTIPLY_ALPHA_WEBGL,b.premultiplyAlpha),t.pixelStorei(n.UNPACK_COLORSPACE_CONVERSION_WEBGL,Qe)}t.pixelStorei(n.UNPACK_ALIGNMENT,b.unpackAlignment);let re=v(b.image,!1,r.maxTextureSize);re=He(b,re);let pe=s.convert(b.format,b.colorSpace),U=s.convert(b.type),se=w(b.internalFormat,pe,U,b.normalized,b.colorSpace,b.isVideoTexture);st(ue,b);let ne,Ae=b.mipmaps,ve=b.isVideoTexture!==!0,Ee=Se.__version===void 0||oe===!0,We=be.dataReady,je=A(b,re);if(b.isDepthTexture)se=y(b.format===Yr,b.type),Ee&&(ve?t.texStorage2D(n.TEXTURE_2D,1,se,re.width,re.height):t.texImage2D(n.TEXTURE_2D,0,se,re.width,re.height,0,pe,U,null));else if(b.isDataTexture)if(Ae.length>0){ve&&Ee&&t.texStorage2D(n.TEXTURE_2D,je,se,Ae[0].width,Ae[0].height);for(let ce=0,ke=Ae.length;ce<ke;ce++)ne=Ae[ce],ve?We&&t.texSubImage2D(n.TEXTURE_2D,ce,0,0,ne.width,ne.height,pe,U,ne.data):t.texImage2D(n.TEXTURE_2D,ce,se,ne.width,ne.height,0,pe,U,ne.data);b.generateMipmaps=!1}else ve?(Ee&&t.texStorage2D(n.TEXTURE_2D,je,se,re.width,re.height),We&&qt(b,re,pe,U)):t.texImage2D(n.TEXTURE_2D,0,se,re.width,re.height,0,pe,U,re.data);else if(b.isCompressedTexture)if(b.isCompressedArrayTexture){ve&&Ee&&t.texStorage3D(n.TEXTURE_2D_ARRAY,je,se,Ae[0].width,Ae[0].height,re.depth);for(let ce=0,ke=Ae.length;ce<ke;ce++)if(ne=Ae[ce],b.format!==nr)if(pe!==null)if(ve){if(We)if(b.layerUpdates.size>0){let Qe=Om(ne.width,ne.height,b.format,b.type);for(let Ie of b.layerUpdates){let ut=ne.data.subarray(Ie*Qe/ne.data.BYTES_PER_ELEMENT,(Ie+1)*Qe/ne.data.BYTES_PER_ELEMENT);t.compressedTexSubImage3D(n.TEXTURE_2D_ARRAY,ce,0,0,Ie,ne.width,ne.height,1,pe,ut)}}else t.compressedTexSubImage3D(n.TEXTURE_2D_ARRAY,ce,0,0,0,ne.width,ne.height,re.depth,pe,ne.data)}else t.compressedTexImage3D(n.TEXTURE_2D_ARRAY,ce,se,ne.width,ne.height,re.depth,0,ne.data,0,0);else Ke("WebGLRenderer: Attempt to load unsupported compressed texture format in .uploadTexture()");else ve?We&&t.texSubImage3D(n.TEXTURE_2D_ARRAY,ce,0,0,0,ne.width,ne.height,re.depth,pe,U,ne.data):t.texImage3D(n.TEXTURE_2D_ARRAY,ce,se,ne.width,ne.height,re.depth,0,pe,U,ne.data);b.layerUpdates.size>0&&b.clearLayerUpdates()}else{ve&&Ee&&t.texStorage2D(n.TEXTURE_2D,je,se,Ae[0].width,Ae[0].height);for(let ce=0,ke=Ae.length;ce<ke;ce++)ne=Ae[ce],b.format!==nr?pe!==null?ve?We&&t.compressedTexSubImage2D(n.TEXTURE_2D,ce,0,0,ne.width,ne.height,pe,ne.data):t.compressedTexImage2D(n.TEXTURE_2D,ce,se,ne.width,ne.height,0,ne.data):Ke("WebGLRenderer: Attempt to load unsupported compressed texture format in .uploadTexture()"):ve?We&&t.texSubImage2D(n.TEXTURE_2D,ce,0,0,ne.width,ne.height,pe,U,ne.data):t.texImage2D(n.TEXTURE_2D,ce,se,ne.width,ne.height,0,pe,U,ne.data)}else if(b.isDataArrayTexture)if(ve){if(Ee&&t.texStorage3D(n.TEXTURE_2D_ARRAY,je,se,re.width,re.height,re.depth),We)if(b.layerUpdates.size>0){let ce=Om(re.width,re.height,b.format,b.type);for(let ke of b.layerUpdates){let Qe=re.data.subarray(ke*ce/re.data.BYTES_PER_ELEMENT,(ke+1)*ce/re.data.BYTES_PER_ELEMENT);t.texSubImage3D(n.TEXTURE_2D_ARRAY,0,0,0,ke,re.width,re.height,1,pe,U,Qe)}b.clearLayerUpdates()}else t.texSubImage3D(n.TEXTURE_2D_ARRAY,0,0,0,0,re.width,re.height,re.depth,pe,U,re.data)}else t.texImage3D(n.TEXTURE_2D_ARRAY,0,se,re.width,re.height,re.depth,0,pe,U,re.data);else if(b.isData3DTexture)ve?(Ee&&t.texStorage3D(n.TEXTURE_3D,je,se,re.width,re.height,re.depth),We&&t.texSubImage3D(n.TEXTURE_3D,0,0,0,0,re.width,re.height,re.depth,pe,U,re.data)):t.texImage3D(n.TEXTURE_3D,0,se,re.width,re.height,re.depth,0,pe,U,re.data);else if(b.isFramebufferTexture){if(Ee)if(ve)t.texStorage2D(n.TEXTURE_2D,je,se,re.width,re.height);else{let ce=re.width,ke=re.height;for(let Qe=0;Qe<je;Qe++)t.texImage2D(n.TEXTURE_2D,Qe,se,ce,ke,0,pe,U,null),ce>>=1,ke>>=1}}else if(b.isHTMLTexture){if("texElementImage2D"in n){let ce=n.canvas;if(ce.hasAttribute("layoutsubtree")||ce.setAttribute("layoutsubtree","true"),re.parentNode!==ce){ce.appendChild(re),h.add(b),ce.onpaint=ke=>{let Qe=ke.changedElements;for(let Ie of h)Qe.includes(Ie.image)&&(Ie.needsUpdate=!0)},ce.requestPaint();return}if(n.texElementImage2D.length===3)n.texElementImage2D(n.TEXTURE_2D,n.RGBA8,re);else{let Qe=n.RGBA,Ie=n.RGBA,ut=n.UNSIGNED_BYTE;n.texElementImage2D(n.TEXTURE_2D,0,Qe,Ie,ut,re)}n.texParameteri(n.TEXTURE_2D,n.TEXTURE_MIN_FILTER,n.LINEAR),n.texParameteri(n.TEXTURE_2D,n.TEXTURE_WRAP_S,n.CLAMP_TO_EDGE),n.texParameteri(n.TEXTURE_2D,n.TEXTURE_WRAP_T,n.CLAMP_TO_EDGE)}}else if(Ae.length>0){if(ve&&Ee){let ce=Ye(Ae[0]);t.texStorage2D(n.TEXTURE_2D,je,se,ce.width,ce.height)}for(let ce=0,ke=Ae.length;ce<ke;ce++)ne=Ae[ce],ve?We&&t.texSubImage2D(n.TEXTURE_2D,ce,0,0,pe,U,ne):t.texImage2D(n.TEXTURE_2D,ce,se,pe,U,ne);b.generateMipmaps=!1}else if(ve){if(Ee){let ce=Ye(re);t.texStorage2D(n.TEXTURE_2D,je,se,ce.width,ce.height)}We&&t.texSubImage2D(n.TEXTURE_2D,0,0,0,pe,U,re)}else t.texImage2D(n.TEXTURE_2D,0,se,pe,U,re);T(b)&&b.mipmapsAutoUpdate===!0&&M(ue),Se.__version=be.version,b.onUpdate&&b.onUpdate(b)}I.__version=b.version}function hn(I,b,X){if(b.image.length!==6)return;let ue=ct(I,b),oe=b.source;t.bindTexture(n.TEXTURE_CUBE_MAP,I.__webglTexture,n.TEXTURE0+X);let be=i.get(oe);if(oe.version!==be.__version||ue===!0){t.activeTexture(n.TEXTURE0+X);let Se=vt.getPrimaries(vt.workingColorSpace),te=b.colorSpace===Zr?null:vt.getPrimaries(b.colorSpace),re=b.colorSpace===Zr||Se===te?n.NONE:n.BROWSER_DEFAULT_WEBGL;t.pixelStorei(n.UNPACK_FLIP_Y_WEBGL,b.flipY),t.pixelStorei(n.UNPACK_PREMULTIPLY_ALPHA_WEBGL,b.premultiplyAlpha),t.pixelStorei(n.UNPACK_ALIGNMENT,b.unpackAlignment),t.pixelStorei(n.UNPACK_COLORSPACE_CONVERSION_WEBGL,re);let pe=b.isCompressedTexture||b.image[0].isCompressedTexture,U=b.image[0]&&b.image[0].isDataTexture,se=[];for(let Ie=0;Ie<6;Ie++)!pe&&!U?se[Ie]=v(b.image[Ie],!0,r.maxCubemapSize):se[Ie]=U?b.image[Ie].image:b.image[Ie],se[Ie]=He(b,se[Ie]);let ne=se[0],Ae=s.convert(b.format,b.colorSpace),ve=s.convert(b.type),Ee=w(b.internalFormat,Ae,ve,b.normalized,b.colorSpace),We=b.isVideoTexture!==!0,je=be.__version===void 0||ue===!0,ce=oe.dataReady,ke=A(b,ne);st(n.TEXTURE_CUBE_MAP,b);let Qe;if(b.isDepthTexture){if(Ee=y(b.format===Yr,b.type),je)if(We)t.texStorage2D(n.TEXTURE_CUBE_MAP,1,Ee,ne.width,ne.height);else for(let Ie=0;Ie<6;Ie++)t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,Ee,ne.width,ne.height,0,Ae,ve,null)}else if(pe){We&&je&&t.texStorage2D(n.TEXTURE_CUBE_MAP,ke,Ee,ne.width,ne.height);for(let Ie=0;Ie<6;Ie++){Qe=se[Ie].mipmaps;for(let ut=0;ut<Qe.length;ut++){let Wt=Qe[ut];b.format!==nr?Ae!==null?We?ce&&t.compressedTexSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,0,0,Wt.width,Wt.height,Ae,Wt.data):t.compressedTexImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,Ee,Wt.width,Wt.height,0,Wt.data):Ke("WebGLRenderer: Attempt to load unsupported compressed texture format in .setTextureCube()"):We?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,0,0,Wt.width,Wt.height,Ae,ve,Wt.data):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut,Ee,Wt.width,Wt.height,0,Ae,ve,Wt.data)}}}else{if(Qe=b.mipmaps,We&&je){Qe.length>0&&ke++;let Ie=Ye(se[0]);t.texStorage2D(n.TEXTURE_CUBE_MAP,ke,Ee,Ie.width,Ie.height)}for(let Ie=0;Ie<6;Ie++)if(U){We?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,0,0,se[Ie].width,se[Ie].height,Ae,ve,se[Ie].data):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,Ee,se[Ie].width,se[Ie].height,0,Ae,ve,se[Ie].data);for(let ut=0;ut<Qe.length;ut++){let jn=Qe[ut].image[Ie].image;We?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,0,0,jn.width,jn.height,Ae,ve,jn.data):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,Ee,jn.width,jn.height,0,Ae,ve,jn.data)}}else{We?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,0,0,Ae,ve,se[Ie]):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,0,Ee,Ae,ve,se[Ie]);for(let ut=0;ut<Qe.length;ut++){let Wt=Qe[ut];We?ce&&t.texSubImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,0,0,Ae,ve,Wt.image[Ie]):t.texImage2D(n.TEXTURE_CUBE_MAP_POSITIVE_X+Ie,ut+1,Ee,Ae,ve,Wt.image[Ie])}}}T(b)&&b.mipmapsAutoUpdate===!0&&M(n.TEXTURE_CUBE_MAP),be.__version=oe.version,b.onUpdate&&b.onUpdate(b)}I.__version=b.version}function Ot(I,b,X,ue,oe,be){let Se=s.convert(X.format,X.colorSpace),te=s.convert(X.type),re=w(X.internalFormat,Se,te,X.normalized,X.colorSpace),pe=i.get(b),U=i.get(X);if(U.__renderTarget=b,!pe.__hasExternalTextures){let se=Math.max(1,b.width>>be),ne=Math.max(1,b.height>>be);oe===n.TEXTURE_3D||oe===n.TEXTURE_2D_ARRAY?t.texImage3D(oe,be,re,se,ne,b.depth,0,Se,te,null):t.texImage2D(oe,be,re,se,ne,0,Se,te,null)}t.bindFramebuffer(n.FRAMEBUFFER,I),we(b)?a.framebufferTexture2DMultisampleEXT(n.FRAMEBUFFER,ue,oe,U.__webglTexture,0,lt(b)):(oe===n.TEXTURE_2D||oe>=n.TEXTURE_CUBE_MAP_POSITIVE_X&&oe<=n.TEXTURE_CUBE_MAP_NEGATIVE_Z)&&n.framebufferTexture2D(n.FRAMEBUFFER,ue,oe,U.__webglTexture,be),t.bindFramebuffer(n.FRAMEBUFFER,null)}function Pn(I,b,X){if(n.bindRenderbuffer(n.RENDERBUFFER,I),b.depthBuffer){let ue=b.depthTexture,oe=ue&&ue.isDepthTexture?ue.type:null,be=y(b.stencilBuffer,oe),Se=b.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT;we(b)?a.renderbufferStorageMultisampleEXT(n.RENDERBUFFER,lt(b),be,b.width,b.height):X?n.renderbufferStorageMultisample(n.RENDERBUFFER,lt(b),be,b.width,b.height):n.renderbufferStorage(n.RENDERBUFFER,be,b.width,b.height),n.framebufferRenderbuffer(n.FRAMEBUFFER,Se,n.RENDERBUFFER,I)}else{let ue=b.textures;for(let oe=0;oe<ue.length;oe++){let be=ue[oe],Se=s.convert(be.format,be.colorSpace),te=s.convert(be.type),re=w(be.internalFormat,Se,te,be.normalized,be.colorSpace);we(b)?a.renderbufferStorageMultisampleEXT(n.RENDERBUFFER,lt(b),re,b.width,b.height):X?n.renderbufferStorageMultisample(n.RENDERBUFFER,lt(b),re,b.width,b.height):n.renderbufferStorage(n.RENDERBUFFER,re,b.width,b.height)}}n.bindRenderbuffer(n.RENDERBUFFER,null)}function St(I,b,X){let ue=b.isWebGLCubeRenderTarget===!0;if(t.bindFramebuffer(n.FRAMEBUFFER,I),!(b.depthTexture&&b.depthTexture.isDepthTexture))throw new Error("THREE.WebGLTextures: renderTarget.depthTexture must be an instance of THREE.DepthTexture.");let oe=i.get(b.depthTexture);oe.__renderTarget=b;let be=ue?b.depthTexture.image[0]:b.depthTexture.image;(!oe.__webglTexture||be.width!==b.width||be.height!==b.height)&&(be.width=b.width,be.height=b.height,b.depthTexture.needsUpdate=!0),ue?_e(b.depthTexture,0):ge(b.depthTexture,0);let Se=oe.__webglTexture,te=lt(b),re=ue?n.TEXTURE_CUBE_MAP_POSITIVE_X+X:n.TEXTURE_2D,pe=b.depthTexture.format===Yr?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT;if(b.depthTexture.format===zr)we(b)?a.framebufferTexture2DMultisampleEXT(n.FRAMEBUFFER,pe,re,Se,0,te):n.framebufferTexture2D(n.FRAMEBUFFER,pe,re,Se,0);else if(b.depthTexture.format===Yr)we(b)?a.framebufferTexture2DMultisampleEXT(n.FRAMEBUFFER,pe,re,Se,0,te):n.framebufferTexture2D(n.FRAMEBUFFER,pe,re,Se,0);else throw new Error("THREE.WebGLTextures: Unknown depthTexture format.")}function En(I){let b=i.get(I),X=I.isWebGLCubeRenderTarget===!0;if(b.__boundDepthTexture!==I.depthTexture){let ue=I.depthTexture;if(b.__depthDisposeCallback&&b.__depthDisposeCallback(),ue){let oe=()=>{delete b.__boundDepthTexture,delete b.__depthDisposeCallback,ue.removeEventListener("dispose",oe)};ue.addEventListener("dispose",oe),b.__depthDisposeCallback=oe}b.__boundDepthTexture=ue}if(I.depthTexture&&!b.__autoAllocateDepthBuffer)if(X)for(let ue=0;ue<6;ue++)St(b.__webglFramebuffer[ue],I,ue);else I.texture.mipmaps.length>0?St(b.__webglFramebuffer[0],I,0):St(b.__webglFramebuffer,I,0);else if(X){b.__webglDepthbuffer=[];for(let ue=0;ue<6;ue++)if(t.bindFramebuffer(n.FRAMEBUFFER,b.__webglFramebuffer[ue]),b.__webglDepthbuffer[ue]===void 0)b.__webglDepthbuffer[ue]=n.createRenderbuffer(),Pn(b.__webglDepthbuffer[ue],I,!1);else{let oe=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT,be=b.__webglDepthbuffer[ue];n.bindRenderbuffer(n.RENDERBUFFER,be),n.framebufferRenderbuffer(n.FRAMEBUFFER,oe,n.RENDERBUFFER,be)}}else if(I.texture.mipmaps.length>0?t.bindFramebuffer(n.FRAMEBUFFER,b.__webglFramebuffer[0]):t.bindFramebuffer(n.FRAMEBUFFER,b.__webglFramebuffer),b.__webglDepthbuffer===void 0)b.__webglDepthbuffer=n.createRenderbuffer(),Pn(b.__webglDepthbuffer,I,!1);else{let oe=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT,be=b.__webglDepthbuffer;n.bindRenderbuffer(n.RENDERBUFFER,be),n.framebufferRenderbuffer(n.FRAMEBUFFER,oe,n.RENDERBUFFER,be)}t.bindFramebuffer(n.FRAMEBUFFER,null)}function tn(I,b,X){let ue=i.get(I);b!==void 0&&Ot(ue.__webglFramebuffer,I,I.texture,n.COLOR_ATTACHMENT0,n.TEXTURE_2D,0),X!==void 0&&En(I)}function fn(I){let b=I.texture,X=i.get(I),ue=i.get(b);I.addEventListener("dispose",H),k(I);let oe=I.textures,be=I.isWebGLCubeRenderTarget===!0,Se=oe.length>1;if(Se||(ue.__webglTexture===void 0&&(ue.__webglTexture=n.createTexture()),ue.__version=b.version,o.memory.textures++),be){X.__webglFramebuffer=[];for(let te=0;te<6;te++)if(b.mipmaps.length>0){X.__webglFramebuffer[te]=[];for(let re=0;re<b.mipmaps.length;re++)X.__webglFramebuffer[te][re]=n.createFramebuffer()}else X.__webglFramebuffer[te]=n.createFramebuffer()}else{if(b.mipmaps.length>0){X.__webglFramebuffer=[];for(let te=0;te<b.mipmaps.length;te++)X.__webglFramebuffer[te]=n.createFramebuffer()}else X.__webglFramebuffer=n.createFramebuffer();if(Se)for(let te=0,re=oe.length;te<re;te++){let pe=i.get(oe[te]);pe.__webglTexture===void 0&&(pe.__webglTexture=n.createTexture(),o.memory.textures++)}if(I.samples>0&&we(I)===!1){X.__webglMultisampledFramebuffer=n.createFramebuffer(),X.__webglColorRenderbuffer=[],t.bindFramebuffer(n.FRAMEBUFFER,X.__webglMultisampledFramebuffer);for(let te=0;te<oe.length;te++){let re=oe[te];X.__webglColorRenderbuffer[te]=n.createRenderbuffer(),n.bindRenderbuffer(n.RENDERBUFFER,X.__webglColorRenderbuffer[te]);let pe=s.convert(re.format,re.colorSpace),U=s.convert(re.type),se=w(re.internalFormat,pe,U,re.normalized,re.colorSpace,I.isXRRenderTarget===!0),ne=lt(I);n.renderbufferStorageMultisample(n.RENDERBUFFER,ne,se,I.width,I.height),n.framebufferRenderbuffer(n.FRAMEBUFFER,n.COLOR_ATTACHMENT0+te,n.RENDERBUFFER,X.__webglColorRenderbuffer[te])}n.bindRenderbuffer(n.RENDERBUFFER,null),I.depthBuffer&&(X.__webglDepthRenderbuffer=n.createRenderbuffer(),Pn(X.__webglDepthRenderbuffer,I,!0)),t.bindFramebuffer(n.FRAMEBUFFER,null)}}if(be){t.bindTexture(n.TEXTURE_CUBE_MAP,ue.__webglTexture),st(n.TEXTURE_CUBE_MAP,b);for(let te=0;te<6;te++)if(b.mipmaps.length>0)for(let re=0;re<b.mipmaps.length;re++)Ot(X.__webglFramebuffer[te][re],I,b,n.COLOR_ATTACHMENT0,n.TEXTURE_CUBE_MAP_POSITIVE_X+te,re);else Ot(X.__webglFramebuffer[te],I,b,n.COLOR_ATTACHMENT0,n.TEXTURE_CUBE_MAP_POSITIVE_X+te,0);T(b)?M(n.TEXTURE_CUBE_MAP):b.mipmaps.length>0&&n.texParameteri(n.TEXTURE_CUBE_MAP,n.TEXTURE_MAX_LEVEL,b.mipmaps.length-1),t.unbindTexture()}else if(Se){for(let te=0,re=oe.length;te<re;te++){let pe=oe[te],U=i.get(pe),se=n.TEXTURE_2D;(I.isWebGL3DRenderTarget||I.isWebGLArrayRenderTarget)&&(se=I.isWebGL3DRenderTarget?n.TEXTURE_3D:n.TEXTURE_2D_ARRAY),t.bindTexture(se,U.__webglTexture),st(se,pe),Ot(X.__webglFramebuffer,I,pe,n.COLOR_ATTACHMENT0+te,se,0),T(pe)&&M(se)}t.unbindTexture()}else{let te=n.TEXTURE_2D;if((I.isWebGL3DRenderTarget||I.isWebGLArrayRenderTarget)&&(te=I.isWebGL3DRenderTarget?n.TEXTURE_3D:n.TEXTURE_2D_ARRAY),t.bindTexture(te,ue.__webglTexture),st(te,b),b.mipmaps.length>0)for(let re=0;re<b.mipmaps.length;re++)Ot(X.__webglFramebuffer[re],I,b,n.COLOR_ATTACHMENT0,te,re);else Ot(X.__webglFramebuffer,I,b,n.COLOR_ATTACHMENT0,te,0);T(b)?M(te):b.mipmaps.length>0&&n.texParameteri(te,n.TEXTURE_MAX_LEVEL,b.mipmaps.length-1),t.unbindTexture()}I.depthBuffer&&En(I)}function O(I){let b=I.textures;for(let X=0,ue=b.length;X<ue;X++){let oe=b[X];if(T(oe)&&oe.mipmapsAutoUpdate===!0){let be=R(I),Se=i.get(oe).__webglTexture;t.bindTexture(be,Se),M(be),t.unbindTexture()}}}let Ce=[];function Ze(I){if(I.samples>0){if(we(I)===!1){let b=I.textures,X=I.width,ue=I.height,oe=n.COLOR_BUFFER_BIT,be=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT,Se=i.get(I),te=b.length>1;if(te)for(let pe=0;pe<b.length;pe++)t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglMultisampledFramebuffer),n.framebufferRenderbuffer(n.FRAMEBUFFER,n.COLOR_ATTACHMENT0+pe,n.RENDERBUFFER,null),t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglFramebuffer),n.framebufferTexture2D(n.DRAW_FRAMEBUFFER,n.COLOR_ATTACHMENT0+pe,n.TEXTURE_2D,null,0);t.bindFramebuffer(n.READ_FRAMEBUFFER,Se.__webglMultisampledFramebuffer),I.texture.mipmaps.length>0?t.bindFramebuffer(n.DRAW_FRAMEBUFFER,Se.__webglFramebuffer[0]):t.bindFramebuffer(n.DRAW_FRAMEBUFFER,Se.__webglFramebuffer);for(let pe=0;pe<b.length;pe++){if(I.resolveDepthBuffer&&(I.depthBuffer&&(oe|=n.DEPTH_BUFFER_BIT),I.stencilBuffer&&I.resolveStencilBuffer&&(oe|=n.STENCIL_BUFFER_BIT)),te){n.framebufferRenderbuffer(n.READ_FRAMEBUFFER,n.COLOR_ATTACHMENT0,n.RENDERBUFFER,Se.__webglColorRenderbuffer[pe]);let U=i.get(b[pe]).__webglTexture;n.framebufferTexture2D(n.DRAW_FRAMEBUFFER,n.COLOR_ATTACHMENT0,n.TEXTURE_2D,U,0)}n.blitFramebuffer(0,0,X,ue,0,0,X,ue,oe,n.NEAREST),l===!0&&(Ce.length=0,Ce.push(n.COLOR_ATTACHMENT0+pe),I.depthBuffer&&I.storeMultisampledDepthBuffer===!1&&Ce.push(be),n.invalidateFramebuffer(n.READ_FRAMEBUFFER,Ce))}if(t.bindFramebuffer(n.READ_FRAMEBUFFER,null),t.bindFramebuffer(n.DRAW_FRAMEBUFFER,null),te)for(let pe=0;pe<b.length;pe++){t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglMultisampledFramebuffer),n.framebufferRenderbuffer(n.FRAMEBUFFER,n.COLOR_ATTACHMENT0+pe,n.RENDERBUFFER,Se.__webglColorRenderbuffer[pe]);let U=i.get(b[pe]).__webglTexture;t.bindFramebuffer(n.FRAMEBUFFER,Se.__webglFramebuffer),n.framebufferTexture2D(n.DRAW_FRAMEBUFFER,n.COLOR_ATTACHMENT0+pe,n.TEXTURE_2D,U,0)}t.bindFramebuffer(n.DRAW_FRAMEBUFFER,Se.__webglMultisampledFramebuffer)}else if(I.depthBuffer&&I.storeMultisampledDepthBuffer===!1&&l){let b=I.stencilBuffer?n.DEPTH_STENCIL_ATTACHMENT:n.DEPTH_ATTACHMENT;n.invalidateFramebuffer(n.DRAW_FRAMEBUFFER,[b])}}}function lt(I){return Math.min(r.maxSamples,I.samples)}function we(I){let b=i.get(I);return I.samples>0&&e.has("WEBGL_multisampled_render_to_texture")===!0&&b.__useRenderToTexture!==!1}function Bt(I){let b=o.render.frame;u.get(I)!==b&&(u.set(I,b),I.update())}function He(I,b){let X=I.colorSpace,ue=I.format,oe=I.type;return I.isCompressedTexture===!0||I.isVideoTexture===!0||X!==dl&&X!==Zr&&(vt.getTransfer(X)===Nt?(ue!==nr||oe!==di)&&Ke("WebGLTextures: sRGB encoded textures have to use RGBAFormat and UnsignedByteType."):nt("WebGLTextures: Unsupported texture color space:",X)),b}function Ye(I){return typeof HTMLImageElement<"u"&&I instanceof HTMLImageElement?(c.width=I.naturalWidth||I.width,c.height=I.naturalHeight||I.height):typeof VideoFrame<"u"&&I instanceof VideoFrame?(c.width=I.displayWidth,c.height=I.displayHeight):(c.width=I.width,c.height=I.height),c}this.allocateTextureUnit=he,this.resetTextureUnits=Q,this.getTextureUnits=ie,this.setTextureUnits=fe,this.setTexture2D=ge,this.setTexture2DArray=ye,this.setTexture3D=xe,this.setTextureCube=_e,this.rebindTextures=tn,this.setupRenderTarget=fn,this.updateRenderTargetMipmap=O,this.updateMultisampleRenderTarget=Ze,this.setupDepthRenderbuffer=En,this.setupFrameBufferTexture=Ot,this.useMultisampledRTT=we,this.dispose=F}function jN(n,e){function t(i,r=Zr){let s,o=vt.getTransfer(r);if(i===di)return n.UNSIGNED_BYTE;if(i===Mh)return n.UNSIGNED_SHORT_4_4_4_4;if(i===Eh)return n.UNSIGNED_SHORT_5_5_5_1;if(i===xm)return n.UNSIGNED_INT_5_9_9_9_REV;if(i===vm)return n.UNSIGNED_INT_10F_11F_11F_REV;if(i===ym)return n.BYTE;if(i===_m)return n.SHORT;if(i===ua)return n.UNSIGNED_SHORT;if(i===Sh)return n.INT;if(i===Qi)return n.UNSIGNED_INT;if(i===er)return n.FLOAT;if(i===tr)return n.HALF_FLOAT;if(i===bm)return n.ALPHA;if(i===Sm)return n.RGB;if(i===nr)return n.RGBA;if(i===zr)return n.DEPTH_COMPONENT;if(i===Yr)return n.DEPTH_STENCIL;if(i===Mm)return n.RED;if(i===wh)return n.RED_INTEGER;if(i===bs)return n.RG;if(i===Ah)return n.RG_INTEGER;if(i===Th)return n.RGBA_INTEGER;if(i===Ol||i===Fl||i===Bl||i===kl)if(o===Nt)if(s=e.get("WEBGL_compressed_texture_s3tc_srgb"),s!==null){if(i===Ol)return s.COMPRESSED_SRGB_S3TC_DXT1_EXT;if(i===Fl)return s.COMPRESSED_SRGB_ALPHA_S3TC_DXT1_EXT;if(i===Bl)return s.COMPRESSED_SRGB_ALPHA_S3TC_DXT3_EXT;if(i===kl)return s.COMPRESSED_SRGB_ALPHA_S3TC_DXT5_EXT}else return null;else if(s=e.get("WEBGL_compressed_texture_s3tc"),s!==null){if(i===Ol)return s.COMPRESSED_RGB_S3TC_DXT1_EXT;if(i===Fl)return s.COMPRESSED_RGBA_S3TC_DXT1_EXT;if(i===Bl)return s.COMPRESSED_RGBA_S3TC_DXT3_EXT;if(i===kl)return s.COMPRESSED_RGBA_S3TC_DXT5_EXT}else return null;if(i===Rh||i===Ih||i===Ch||i===Nh)if(s=e.get("WEBGL_compressed_texture_pvrtc"),s!==null){if(i===Rh)return s.COMPRESSED_RGB_PVRTC_4BPPV1_IMG;if(i===Ih)return s.COMPRESSED_RGB_PVRTC_2BPPV1_IMG;if(i===Ch)return s.COMPRESSED_RGBA_PVRTC_4BPPV1_IMG;if(i===Nh)return s.COMPRESSED_RGBA_PVRTC_2BPPV1_IMG}else return null;if(i===Ph||i===Lh||i===Dh||i===Uh||i===Oh||i===Vl||i===Fh)if(s=e.get("WEBGL_compressed_texture_etc"),s!==null){if(i===Ph||i===Lh)return o===Nt?s.COMPRESSED_SRGB8_ETC2:s.COMPRESSED_RGB8_ETC2;if(i===Dh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ETC2_EAC:s.COMPRESSED_RGBA8_ETC2_EAC;if(i===Uh)return s.COMPRESSED_R11_EAC;if(i===Oh)return s.COMPRESSED_SIGNED_R11_EAC;if(i===Vl)return s.COMPRESSED_RG11_EAC;if(i===Fh)return s.COMPRESSED_SIGNED_RG11_EAC}else return null;if(i===Bh||i===kh||i===Vh||i===Gh||i===zh||i===Hh||i===Wh||i===Xh||i===Yh||i===Zh||i===Kh||i===$h||i===qh||i===Jh)if(s=e.get("WEBGL_compressed_texture_astc"),s!==null){if(i===Bh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_4x4_KHR:s.COMPRESSED_RGBA_ASTC_4x4_KHR;if(i===kh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_5x4_KHR:s.COMPRESSED_RGBA_ASTC_5x4_KHR;if(i===Vh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_5x5_KHR:s.COMPRESSED_RGBA_ASTC_5x5_KHR;if(i===Gh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_6x5_KHR:s.COMPRESSED_RGBA_ASTC_6x5_KHR;if(i===zh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_6x6_KHR:s.COMPRESSED_RGBA_ASTC_6x6_KHR;if(i===Hh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_8x5_KHR:s.COMPRESSED_RGBA_ASTC_8x5_KHR;if(i===Wh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_8x6_KHR:s.COMPRESSED_RGBA_ASTC_8x6_KHR;if(i===Xh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_8x8_KHR:s.COMPRESSED_RGBA_ASTC_8x8_KHR;if(i===Yh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x5_KHR:s.COMPRESSED_RGBA_ASTC_10x5_KHR;if(i===Zh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x6_KHR:s.COMPRESSED_RGBA_ASTC_10x6_KHR;if(i===Kh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x8_KHR:s.COMPRESSED_RGBA_ASTC_10x8_KHR;if(i===$h)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_10x10_KHR:s.COMPRESSED_RGBA_ASTC_10x10_KHR;if(i===qh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_12x10_KHR:s.COMPRESSED_RGBA_ASTC_12x10_KHR;if(i===Jh)return o===Nt?s.COMPRESSED_SRGB8_ALPHA8_ASTC_12x12_KHR:s.COMPRESSED_RGBA_ASTC_12x12_KHR}else return null;if(i===jh||i===Qh||i===ef)if(s=e.get("EXT_texture_compression_bptc"),s!==null){if(i===jh)return o===Nt?s.COMPRESSED_SRGB_ALPHA_BPTC_UNORM_EXT:s.COMPRESSED_RGBA_BPTC_UNORM_EXT;if(i===Qh)return s.COMPRESSED_RGB_BPTC_SIGNED_FLOAT_EXT;if(i===ef)return s.COMPRESSED_RGB_BPTC_UNSIGNED_FLOAT_EXT}else return null;if(i===tf||i===nf||i===Gl||i===rf)if(s=e.get("EXT_texture_compression_rgtc"),s!==null){if(i===tf)return s.COMPRESSED_RED_RGTC1_EXT;if(i===nf)return s.COMPRESSED_SIGNED_RED_RGTC1_EXT;if(i===Gl)return s.COMPRESSED_RED_GREEN_RGTC2_EXT;if(i===rf)return s.COMPRESSED_SIGNED_RED_GREEN_RGTC2_EXT}else return null;return i===$s?n.UNSIGNED_INT_24_8:n[i]!==void 0?n[i]:null}return{convert:t}}var QN=`
void main() {

	gl_Position = vec4( position, 1.0 );

}`,e2=`
uniform sampler2DArray depthColor;
uniform float depthWidth;
uniform float depthHeight;

void main() {

	vec2 coord = vec2( gl_FragCoord.x / depthWidth, gl_FragCoord.y / depthHeight );

	if ( coord.x >= 1.0 ) {

		gl_FragDepth = texture( depthColor, vec3( coord.x - 1.0, coord.y, 1 ) ).r;

	} else {

		gl_FragDepth = texture( depthColor, vec3( coord.x, coord.y, 0 ) ).r;

	}

}`,Xm=class{constructor(){this.texture=null,this.mesh=null,this.depthNear=0,this.depthFar=0}init(e,t){if(this.texture===null){let i=new wl(e.texture);(e.depthNear!==t.depthNear||e.depthFar!==t.depthFar)&&(this.depthNear=e.depthNear,this.depthFar=e.depthFar),this.texture=i}}getMesh(e){if(this.texture!==null&&this.mesh===null){let t=e.cameras[0].viewport,i=new vr({vertexShader:QN,fragmentShader:e2,uniforms:{depthColor:{value:this.texture},depthWidth:{value:t.z},depthHeight:{value:t.w}}});this.mesh=new Ti(new Al(20,20),i)}return this.mesh}reset(){this.texture=null,this.mesh=null}getDepthTexture(){return this.texture}},Ym=class extends ji{constructor(e,t){super();let i=this,r=null,s=1,o=null,a="local-floor",l=1,c=null,u=null,h=null,f=null,d=null,p=null,x=typeof XRWebGLBinding<"u",m=new Xm,g={},v=t.getContextAttributes(),T=null,M=null,R=[],w=[],y=new it,A=null,k=null,D=new ai;D.viewport=new jt;let L=new ai;L.viewport=new jt;let H=[D,L],z=new yh,N=null,F=null;this.cameraAutoUpdate=!0,this.enabled=!1,this.isPresenting=!1,this.getController=function(ee){let ge=R[ee];return ge===void 0&&(ge=new Qo,R[ee]=ge),ge.getTargetRaySpace()},this.getControllerGrip=function(ee){let ge=R[ee];return ge===void 0&&(ge=new Qo,R[ee]=ge),ge.getGripSpace()},this.getHand=function(ee){let ge=R[ee];return ge===void 0&&(ge=new Qo,R[ee]=ge),ge.getHandSpace()};function Z(ee){let ge=w.indexOf(ee.inputSource);if(ge===-1)return;let ye=R[ge];ye!==void 0&&(ye.update(ee.inputSource,ee.frame,c||o),ye.dispatchEvent({type:ee.type,data:ee.inputSource}))}function V(){r.removeEventListener("select",Z),r.removeEventListener("selectstart",Z),r.removeEventListener("selectend",Z),r.removeEventListener("squeeze",Z),r.removeEventListener("squeezestart",Z),r.removeEventListener("squeezeend",Z),r.removeEventListener("end",V),r.removeEventListener("inputsourceschange",le);for(let ee=0;ee<R.length;ee++){let ge=w[ee];ge!==null&&(w[ee]=null,R[ee].disconnect(ge))}N=null,F=null,m.reset();for(let ee in g)delete g[ee];if(e.setRenderTarget(T),d=null,f=null,h=null,r=null,M=null,he.stop(),i.isPresenting=!1,e.setPixelRatio(A),e.setSize(y.width,y.height,!1),k!==null){let ee=k.camera;ee.fov=k.fov,ee.zoom=k.zoom,ee.updateProjectionMatrix(),k=null}i.dispatchEvent({type:"sessionend"})}this.setFramebufferScaleFactor=function(ee){s=ee,i.isPresenting===!0&&Ke("WebXRManager: Cannot change framebuffer scale while presenting.")},this.setReferenceSpaceType=function(ee){a=ee,i.isPresenting===!0&&Ke("WebXRManager: Cannot change reference space type while presenting.")},this.getReferenceSpace=function(){return c||o},this.setReferenceSpace=function(ee){c=ee},this.getBaseLayer=function(){return f!==null?f:d},this.getBinding=function(){return h===null&&x&&(h=new XRWebGLBinding(r,t)),h},this.getFrame=function(){return p},this.getSession=function(){return r},this.setSession=async function(ee){if(r=ee,r!==null){if(T=e.getRenderTarget(),r.addEventListener("select",Z),r.addEventListener("selectstart",Z),r.addEventListener("selectend",Z),r.addEventListener("squeeze",Z),r.addEventListener("squeezestart",Z),r.addEventListener("squeezeend",Z),r.addEventListener("end",V),r.addEventListener("inputsourceschange",le),v.xrCompatible!==!0&&await t.makeXRCompatible(),A=e.getPixelRatio(),e.getSize(y),x&&"createProjectionLayer"in XRWebGLBinding.prototype){let ye=null,xe=null,_e=null;v.depth&&(_e=v.stencil?t.DEPTH24_STENCIL8:t.DEPTH_COMPONENT24,ye=v.stencil?Yr:zr,xe=v.stencil?$s:Qi);let ze={colorFormat:t.RGBA8,depthFormat:_e,scaleFactor:s};h=this.getBinding(),f=h.createProjectionLayer(ze),r.updateRenderState({layers:[f]}),e.setPixelRatio(1),e.setSize(f.textureWidth,f.textureHeight,!1),M=new Ai(f.textureWidth,f.textureHeight,{format:nr,type:di,depthTexture:new Wr(f.textureWidth,f.textureHeight,xe,void 0,void 0,void 0,void 0,void 0,void 0,ye),stencilBuffer:v.stencil,colorSpace:e.outputColorSpace,samples:v.antialias?4:0,resolveDepthBuffer:f.ignoreDepthValues===!1,resolveStencilBuffer:f.ignoreDepthValues===!1,storeMultisampledDepthBuffer:f.ignoreDepthValues===!1,storeMultisampledStencilBuffer:f.ignoreDepthValues===!1})}else{let ye={antialias:v.antialias,alpha:!0,depth:v.depth,stencil:v.stencil,framebufferScaleFactor:s};d=new XRWebGLLayer(r,t,ye),r.updateRenderState({baseLayer:d}),e.setPixelRatio(1),e.setSize(d.framebufferWidth,d.framebufferHeight,!1),M=new Ai(d.framebufferWidth,d.framebufferHeight,{format:nr,type:di,colorSpace:e.outputColorSpace,stencilBuffer:v.stencil,resolveDepthBuffer:d.ignoreDepthValues===!1,resolveStencilBuffer:d.ignoreDepthValues===!1,storeMultisampledDepthBuffer:d.ignoreDepthValues===!1,storeMultisampledStencilBuffer:d.ignoreDepthValues===!1})}M.isXRRenderTarget=!0,this.setFoveation(l),c=null,o=await r.requestReferenceSpace(a),he.setContext(r),he.start(),i.isPresenting=!0,i.dispatchEvent({type:"sessionstart"})}},this.getEnvironmentBlendMode=function(){if(r!==null)return r.environmentBlendMode},this.getDepthTexture=function(){return m.getDepthTexture()};function le(ee){for(let ge=0;ge<ee.removed.length;ge++){let ye=ee.removed[ge],xe=w.indexOf(ye);xe>=0&&(w[xe]=null,R[xe].disconnect(ye))}for(let ge=0;ge<ee.added.length;ge++){let ye=ee.added[ge],xe=w.indexOf(ye);if(xe===-1){for(let ze=0;ze<R.length;ze++)if(ze>=w.length){w.push(ye),xe=ze;break}else if(w[ze]===null){w[ze]=ye,xe=ze;break}if(xe===-1)break}let _e=R[xe];_e&&_e.connect(ye)}}function q(ee,ge){ge===null?ee.matrixWorld.copy(ee.matrix):ee.matrixWorld.multiplyMatrices(ge.matrixWorld,ee.matrix),ee.matrixWorldInverse.copy(ee.matrixWorld).invert()}this.updateCamera=function(ee){if(r===null)return;let ge=ee.near,ye=ee.far;m.texture!==null&&(m.depthNear>0&&(ge=m.depthNear),m.depthFar>0&&(ye=m.depthFar)),z.near=L.near=D.near=ge,z.far=L.far=D.far=ye,(N!==z.near||F!==z.far)&&(r.updateRenderState({depthNear:z.near,depthFar:z.far}),N=z.near,F=z.far),z.layers.mask=ee.layers.mask|6,D.layers.mask=z.layers.mask&-5,L.layers.mask=z.layers.mask&-3;let xe=ee.parent,_e=z.cameras;q(z,xe);for(let ze=0;ze<_e.length;ze++)q(_e[ze],xe);z.projectionMatrix.copy(D.projectionMatrix),z.projectionMatrixInverse.copy(D.projectionMatrixInverse),k===null&&ee.isPerspectiveCamera&&(k={camera:ee,fov:ee.fov,zoom:ee.zoom}),Q(ee,z,xe)};function Q(ee,ge,ye){ye===null?ee.matrix.copy(ge.matrixWorld):(ee.matrix.copy(ye.matrixWorld),ee.matrix.invert(),ee.matrix.multiply(ge.matrixWorld)),ee.matrix.decompose(ee.position,ee.quaternion,ee.scale),ee.updateMatrixWorld(!0),ee.projectionMatrix.copy(ge.projectionMatrix),ee.projectionMatrixInverse.copy(ge.projectionMatrixInverse),ee.isPerspectiveCamera&&(ee.fov=Jo*2*Math.atan(1/ee.projectionMatrix.elements[5]),ee.zoom=1)}this.getCamera=function(){return z},this.getFoveation=function(){if(!(f===null&&d===null))return l},this.setFoveation=function(ee){l=ee,f!==null&&(f.fixedFoveation=ee),d!==null&&d.fixedFoveation!==void 0&&(d.fixedFoveation=ee)},this.hasDepthSensing=function(){return m.texture!==null},this.getDepthSensingMesh=function(){return m.getMesh(z)},this.getCameraTexture=function(ee){return g[ee]};let ie=null;function fe(ee,ge){if(u=ge.getViewerPose(c||o),p=ge,u!==null){let ye=u.views;d!==null&&(e.setRenderTargetFramebuffer(M,d.framebuffer),e.setRenderTarget(M));let xe=!1;ye.length!==z.cameras.length&&(z.cameras.length=0,xe=!0);for(let Fe=0;Fe<ye.length;Fe++){let st=ye[Fe],ct=null;if(d!==null)ct=d.getViewport(st);else{let qt=h.getViewSubImage(f,st);ct=qt.viewport,Fe===0&&(e.setRenderTargetTextures(M,qt.colorTexture,qt.depthStencilTexture),e.setRenderTarget(M))}let ot=H[Fe];ot===void 0&&(ot=new ai,ot.layers.enable(Fe),ot.viewport=new jt,H[Fe]=ot),ot.matrix.fromArray(st.transform.matrix),ot.matrix.decompose(ot.position,ot.quaternion,ot.scale),ot.projectionMatrix.fromArray(st.projectionMatrix),ot.projectionMatrixInverse.copy(ot.projectionMatrix).invert(),ot.viewport.set(ct.x,ct.y,ct.width,ct.height),Fe===0&&(z.matrix.copy(ot.matrix),z.matrix.decompose(z.position,z.quaternion,z.scale)),xe===!0&&z.cameras.push(ot)}let _e=r.enabledFeatures;if(_e&&_e.includes("depth-sensing")&&r.depthUsage=="gpu-optimized"&&x){h=i.getBinding();let Fe=h.getDepthInformation(ye[0]);Fe&&Fe.isValid&&Fe.texture&&m.init(Fe,r.renderState)}if(_e&&_e.includes("camera-access")&&x){e.state.unbindTexture(),h=i.getBinding();for(let Fe=0;Fe<ye.length;Fe++){let st=ye[Fe].camera;if(st){let ct=g[st];ct||(ct=new wl,g[st]=ct);let ot=h.getCameraImage(st);ct.sourceTexture=ot}}}}for(let ye=0;ye<R.length;ye++){let xe=w[ye],_e=R[ye];xe!==null&&_e!==void 0&&_e.update(xe,ge,c||o)}ie&&ie(ee,ge),ge.detectedPlanes&&i.dispatchEvent({type:"planesdetected",data:ge}),p=null}let he=new Wb;he.setAnimationLoop(fe),this.setAnimationLoop=function(ee){ie=ee},this.dispose=function(){}}},t2=new Ht,eS=new rt;eS.set(-1,0,0,0,1,0,0,0,1);function n2(n,e){function t(m,g){m.matrixAutoUpdate===!0&&m.updateMatrix(),g.value.copy(m.matrix)}function i(m,g){g.color.getRGB(m.fogColor.value,Lm(n)),g.isFog?(m.fogNear.value=g.near,m.fogFar.value=g.far):g.isFogExp2&&(m.fogDensity.value=g.density)}function r(m,g,v,T,M){g.isNodeMaterial?g.uniformsNeedUpdate=!1:g.isMeshBasicMaterial?s(m,g):g.isMeshLambertMaterial?(s(m,g),g.envMap&&(m.envMapIntensity.value=g.envMapIntensity)):g.isMeshToonMaterial?(s(m,g),h(m,g)):g.isMeshPhongMaterial?(s(m,g),u(m,g),g.envMap&&(m.envMapIntensity.value=g.envMapIntensity)):g.isMeshStandardMaterial?(s(m,g),f(m,g),g.isMeshPhysicalMaterial&&d(m,g,M)):g.isMeshMatcapMaterial?(s(m,g),p(m,g)):g.isMeshDepthMaterial?s(m,g):g.isMeshDistanceMaterial?(s(m,g),x(m,g)):g.isMeshNormalMaterial?s(m,g):g.isLineBasicMaterial?(o(m,g),g.isLineDashedMaterial&&a(m,g)):g.isPointsMaterial?l(m,g,v,T):g.isSpriteMaterial?c(m,g):g.isShadowMaterial?(m.color.value.copy(g.color),m.opacity.value=g.opacity):g.isShaderMaterial&&(g.uniformsNeedUpdate=!1)}function s(m,g){m.opacity.value=g.opacity,g.color&&m.diffuse.value.copy(g.color),g.emissive&&m.emissive.value.copy(g.emissive).multiplyScalar(g.emissiveIntensity),g.map&&(m.map.value=g.map,t(g.map,m.mapTransform)),g.alphaMap&&(m.alphaMap.value=g.alphaMap,t(g.alphaMap,m.alphaMapTransform)),g.bumpMap&&(m.bumpMap.value=g.bumpMap,t(g.bumpMap,m.bumpMapTransform),m.bumpScale.value=g.bumpScale,g.side===ui&&(m.bumpScale.value*=-1)),g.normalMap&&(m.normalMap.value=g.normalMap,t(g.normalMap,m.normalMapTransform),m.normalScale.value.copy(g.normalScale),g.side===ui&&m.normalScale.value.negate()),g.displacementMap&&(m.displacementMap.value=g.displacementMap,t(g.displacementMap,m.displacementMapTransform),m.displacementScale.value=g.displacementScale,m.displacementBias.value=g.displacementBias),g.emissiveMap&&(m.emissiveMap.value=g.emissiveMap,t(g.emissiveMap,m.emissiveMapTransform)),g.specularMap&&(m.specularMap.value=g.specularMap,t(g.specularMap,m.specularMapTransform)),g.alphaTest>0&&(m.alphaTest.value=g.alphaTest);let v=e.get(g),T=v.envMap,M=v.envMapRotation;T&&(m.envMap.value=T,m.envMapRotation.value.setFromMatrix4(t2.makeRotationFromEuler(M)).transpose(),T.isCubeTexture&&T.isRenderTargetTexture===!1&&m.envMapRotation.value.premultiply(eS),m.reflectivity.value=g.reflectivity,m.ior.value=g.ior,m.refractionRatio.value=g.refractionRatio),g.lightMap&&(m.lightMap.value=g.lightMap,m.lightMapIntensity.value=g.lightMapIntensity,t(g.lightMap,m.lightMapTransform)),g.aoMap&&(m.aoMap.value=g.aoMap,m.aoMapIntensity.value=g.aoMapIntensity,t(g.aoMap,m.aoMapTransform))}function o(m,g){m.diffuse.value.copy(g.color),m.opacity.value=g.opacity,g.map&&(m.map.value=g.map,t(g.map,m.mapTransform))}function a(m,g){m.dashSize.value=g.dashSize,m.totalSize.value=g.dashSize+g.gapSize,m.scale.value=g.scale}function l(m,g,v,T){m.diffuse.value.copy(g.color),m.opacity.value=g.opacity,m.size.value=g.size*v,m.scale.value=T*.5,g.map&&(m.map.value=g.map,t(g.map,m.uvTransform)),g.alphaMap&&(m.alphaMap.value=g.alphaMap,t(g.alphaMap,m.alphaMapTransform)),g.alphaTest>0&&(m.alphaTest.value=g.alphaTest)}function c(m,g){m.diffuse.value.copy(g.color),m.opacity.value=g.opacity,m.rotation.value=g.rotation,g.map&&(m.map.value=g.map,t(g.map,m.mapTransform)),g.alphaMap&&(m.alphaMap.value=g.alphaMap,t(g.alphaMap,m.alphaMapTransform)),g.alphaTest>0&&(m.alphaTest.value=g.alphaTest)}function u(m,g){m.specular.value.copy(g.specular),m.shininess.value=Math.max(g.shininess,1e-4)}function h(m,g){g.gradientMap&&(m.gradientMap.value=g.gradientMap)}function f(m,g){m.metalness.value=g.metalness,g.metalnessMap&&(m.metalnessMap.value=g.metalnessMap,t(g.metalnessMap,m.metalnessMapTransform)),m.roughness.value=g.roughness,g.roughnessMap&&(m.roughnessMap.value=g.roughnessMap,t(g.roughnessMap,m.roughnessMapTransform)),g.envMap&&(m.envMapIntensity.value=g.envMapIntensity)}function d(m,g,v){m.ior.value=g.ior,g.diffuseRoughness>0&&(m.diffuseRoughness.value=g.diffuseRoughness,g.diffuseRoughnessMap&&(m.diffuseRoughnessMap.value=g.diffuseRoughnessMap,t(g.diffuseRoughnessMap,m.diffuseRoughnessMapTransform))),g.sheen>0&&(m.sheenColor.value.copy(g.sheenColor).multiplyScalar(g.sheen),m.sheenRoughness.value=g.sheenRoughness,g.sheenColorMap&&(m.sheenColorMap.value=g.sheenColorMap,t(g.sheenColorMap,m.sheenColorMapTransform)),g.sheenRoughnessMap&&(m.sheenRoughnessMap.value=g.sheenRoughnessMap,t(g.sheenRoughnessMap,m.sheenRoughnessMapTransform))),g.clearcoat>0&&(m.clearcoat.value=g.clearcoat,m.clearcoatRoughness.value=g.clearcoatRoughness,g.clearcoatMap&&(m.clearcoatMap.value=g.clearcoatMap,t(g.clearcoatMap,m.clearcoatMapTransform)),g.clearcoatRoughnessMap&&(m.clearcoatRoughnessMap.value=g.clearcoatRoughnessMap,t(g.clearcoatRoughnessMap,m.clearcoatRoughnessMapTransform)),g.clearcoatNormalMap&&(m.clearcoatNormalMap.value=g.clearcoatNormalMap,t(g.clearcoatNormalMap,m.clearcoatNormalMapTransform),m.clearcoatNormalScale.value.copy(g.clearcoatNormalScale),g.side===ui&&m.clearcoatNormalScale.value.negate())),g.dispersion>0&&(m.dispersion.value=g.dispersion),g.retroreflectivity>0&&(m.retroreflectivity.value=g.retroreflectivity),g.iridescence>0&&(m.iridescence.value=g.iridescence,m.iridescenceIOR.value=g.iridescenceIOR,m.iridescenceThicknessMinimum.value=g.iridescenceThicknessMinimum,m.iridescenceThicknessMaximum.value=g.iridescenceThicknessMaximum,g.iridescenceMap&&(m.iridescenceMap.value=g.iridescenceMap,t(g.iridescenceMap,m.iridescenceMapTransform)),g.iridescenceThicknessMap&&(m.iridescenceThicknessMap.value=g.iridescenceThicknessMap,t(g.iridescenceThicknessMap,m.iridescenceThicknessMapTransform))),g.transmission>0&&(m.transmission.value=g.transmission,m.transmissionSamplerMap.value=v.texture,m.transmissionSamplerSize.value.set(v.width,v.height),g.transmissionMap&&(m.transmissionMap.value=g.transmissionMap,t(g.transmissionMap,m.transmissionMapTransform)),m.thickness.value=g.thickness,g.thicknessMap&&(m.thicknessMap.value=g.thicknessMap,t(g.thicknessMap,m.thicknessMapTransform)),m.attenuationDistance.value=g.attenuationDistance,m.attenuationColor.value.copy(g.attenuationColor)),g.anisotropy>0&&(m.anisotropyVector.value.set(g.anisotropy*Math.cos(g.anisotropyRotation),g.anisotropy*Math.sin(g.anisotropyRotation)),g.anisotropyMap&&(m.anisotropyMap.value=g.anisotropyMap,t(g.anisotropyMap,m.anisotropyMapTransform))),m.specularIntensity.value=g.specularIntensity,m.specularColor.value.copy(g.specularColor),g.specularColorMap&&(m.specularColorMap.value=g.specularColorMap,t(g.specularColorMap,m.specularColorMapTransform)),g.specularIntensityMap&&(m.specularIntensityMap.value=g.specularIntensityMap,t(g.specularIntensityMap,m.specularIntensityMapTransform))}function p(m,g){g.matcap&&(m.matcap.value=g.matcap)}function x(m,g){let v=e.get(g).light;m.referencePosition.value.setFromMatrixPosition(v.matrixWorld),m.nearDistance.value=v.shadow.camera.near,m.farDistance.value=v.shadow.camera.far}return{refreshFogUniforms:i,refreshMaterialUniforms:r}}function i2(n,e,t,i){let r={},s={};function o(v,T){let M=T.program;i.uniformBlockBinding(v,M,r[v.id])}function a(v,T){let M=r[v.id];M===void 0&&(p(v),M=l(v),r[v.id]=M,v.addEventListener("dispose",m));let R=T.program;i.updateUBOMapping(v,R);let w=e.render.frame;s[v.id]!==w&&(c(v),s[v.id]=w)}function l(v){let T=n.createBuffer(),M=v.__size,R=v.usage;return n.bindBuffer(n.UNIFORM_BUFFER,T),n.bufferData(n.UNIFORM_BUFFER,M,R),n.bindBuffer(n.UNIFORM_BUFFER,null),T}function c(v){let T=r[v.id],M=v.uniforms,R=v.__cache;n.bindBuffer(n.UNIFORM_BUFFER,T);for(let w=0,y=M.length;w<y;w++){let A=M[w];if(Array.isArray(A))for(let k=0,D=A.length;k<D;k++)u(A[k],w,k,R);else u(A,w,0,R)}n.bindBuffer(n.UNIFORM_BUFFER,null)}function u(v,T,M,R){if(f(v,T,M,R)===!0){let w=v.__offset,y=v.value;if(Array.isArray(y)){let A=0;for(let k=0;k<y.length;k++){let D=y[k],L=x(D,!0);h(D,v.__data,A),A+=L.storage/Float32Array.BYTES_PER_ELEMENT}}else h(y,v.__data,0);n.bufferSubData(n.UNIFORM_BUFFER,w,v.__data)}}function h(v,T,M){typeof v=="number"||typeof v=="boolean"?T[M]=v:v.isMatrix3?(T[M]=v.elements[0],T[M+1]=v.elements[1],T[M+2]=v.elements[2],T[M+3]=0,T[M+4]=v.elements[3],T[M+5]=v.elements[4],T[M+6]=v.elements[5],T[M+7]=0,T[M+8]=v.elements[6],T[M+9]=v.elements[7],T[M+10]=v.elements[8],T[M+11]=0):ArrayBuffer.isView(v)?T.set(v.subarray(0,T.length-M),M):v.toArray(T,M)}function f(v,T,M,R){let w=v.value,y=T+"_"+M;if(Array.isArray(w)){R[y]===void 0&&(R[y]=[]);let A=R[y],k=!1;for(let D=0;D<w.length;D++)d(w[D],A,D)===!0&&(k=!0);return k}return d(w,R,y)}function d(v,T,M){if(T[M]===void 0)return typeof v=="number"||typeof v=="boolean"?T[M]=v:ArrayBuffer.isView(v)?T[M]=v.slice():T[M]=v.clone(),!0;{let R=T[M];if(typeof v=="number"||typeof v=="boolean"){if(R!==v)return T[M]=v,!0}else{if(ArrayBuffer.isView(v))return!0;if(R.equals(v)===!1)return R.copy(v),!0}}return!1}function p(v){let T=v.uniforms,M=0,R=16;for(let y=0,A=T.length;y<A;y++){let k=Array.isArray(T[y])?T[y]:[T[y]];for(let D=0,L=k.length;D<L;D++){let H=k[D],z=Array.isArray(H.value)?H.value:[H.value],N=Array.isArray(T[y])||Array.isArray(H.value),F=M;for(let V=0,le=z.length;V<le;V++){let q=z[V],Q=x(q,N),ie=M%R,fe=ie%Q.boundary,he=ie+fe;M+=fe,he!==0&&R-he<Q.storage&&(M+=R-he),V===0&&(F=M),M+=Q.storage}let Z=H.type==="int"?Int32Array:H.type==="uint"?Uint32Array:Float32Array;H.__data=new Z((M-F)/Float32Array.BYTES_PER_ELEMENT),H.__offset=F}}let w=M%R;return w>0&&(M+=R-w),v.__size=M,v.__cache={},this}function x(v,T){let M={boundary:0,storage:0};return typeof v=="number"||typeof v=="boolean"?(M.boundary=4,M.storage=4):v.isVector2?(M.boundary=8,M.storage=8):v.isVector3||v.isColor?(M.boundary=16,M.storage=12):v.isVector4?(M.boundary=16,M.storage=16):v.isMatrix3?(M.boundary=16,M.storage=48):v.isMatrix4?(M.boundary=16,M.storage=64):v.isTexture?Ke("WebGLRenderer: Texture samplers can not be part of an uniforms group."):ArrayBuffer.isView(v)?(M.boundary=16,M.storage=v.byteLength):Ke("WebGLRenderer: Unsupported uniform value type.",v),T===!0&&(M.boundary=16,M.storage=Math.ceil(M.storage/16)*16),M}function m(v){let T=v.target;T.removeEventListener("dispose",m),n.deleteBuffer(r[T.id]),delete r[T.id],delete s[T.id]}function g(){for(let v in r)n.deleteBuffer(r[v]);r={},s={}}return{bind:o,update:a,dispose:g}}var r2=new Uint16Array([12469,15057,12620,14925,13266,14620,13807,14376,14323,13990,14545,13625,14713,13328,14840,12882,14931,12528,14996,12233,15039,11829,15066,11525,15080,11295,15085,10976,15082,10705,15073,10495,13880,14564,13898,14542,13977,14430,14158,14124,14393,13732,14556,13410,14702,12996,14814,12596,14891,12291,14937,11834,14957,11489,14958,11194,14943,10803,14921,10506,14893,10278,14858,9960,14484,14039,14487,14025,14499,13941,14524,13740,14574,13468,14654,13106,14743,12678,14818,12344,14867,11893,14889,11509,14893,11180,14881,10751,14852,10428,14812,10128,14765,9754,14712,9466,14764,13480,14764,13475,14766,13440,14766,13347,14769,13070,14786,12713,14816,12387,14844,11957,14860,11549,14868,11215,14855,10751,14825,10403,14782,10044,14729,9651,14666,9352,14599,9029,14967,12835,14966,12831,14963,12804,14954,12723,14936,12564,14917,12347,14900,11958,14886,11569,14878,11247,14859,10765,14828,10401,14784,10011,14727,9600,14660,9289,14586,8893,14508,8533,15111,12234,15110,12234,15104,12216,15092,12156,15067,12010,15028,11776,14981,11500,14942,11205,14902,10752,14861,10393,14812,9991,14752,9570,14682,9252,14603,8808,14519,8445,14431,8145,15209,11449,15208,11451,15202,11451,15190,11438,15163,11384,15117,11274,15055,10979,14994,10648,14932,10343,14871,9936,14803,9532,14729,9218,14645,8742,14556,8381,14461,8020,14365,7603,15273,10603,15272,10607,15267,10619,15256,10631,15231,10614,15182,10535,15118,10389,15042,10167,14963,9787,14883,9447,14800,9115,14710,8665,14615,8318,14514,7911,14411,7507,14279,7198,15314,9675,15313,9683,15309,9712,15298,9759,15277,9797,15229,9773,15166,9668,15084,9487,14995,9274,14898,8910,14800,8539,14697,8234,14590,7790,14479,7409,14367,7067,14178,6621,15337,8619,15337,8631,15333,8677,15325,8769,15305,8871,15264,8940,15202,8909,15119,8775,15022,8565,14916,8328,14804,8009,14688,7614,14569,7287,14448,6888,14321,6483,14088,6171,15350,7402,15350,7419,15347,7480,15340,7613,15322,7804,15287,7973,15229,8057,15148,8012,15046,7846,14933,7611,14810,7357,14682,7069,14552,6656,14421,6316,14251,5948,14007,5528,15356,5942,15356,5977,15353,6119,15348,6294,15332,6551,15302,6824,15249,7044,15171,7122,15070,7050,14949,6861,14818,6611,14679,6349,14538,6067,14398,5651,14189,5311,13935,4958,15359,4123,15359,4153,15356,4296,15353,4646,15338,5160,15311,5508,15263,5829,15188,6042,15088,6094,14966,6001,14826,5796,14678,5543,14527,5287,14377,4985,14133,4586,13869,4257,15360,1563,15360,1642,15358,2076,15354,2636,15341,3350,15317,4019,15273,4429,15203,4732,15105,4911,14981,4932,14836,4818,14679,4621,14517,4386,14359,4156,14083,3795,13808,3437,15360,122,15360,137,15358,285,15355,636,15344,1274,15322,2177,15281,2765,15215,3223,15120,3451,14995,3569,14846,3567,14681,3466,14511,3305,14344,3121,14037,2800,13753,2467,15360,0,15360,1,15359,21,15355,89,15346,253,15325,479,15287,796,15225,1148,15133,1492,15008,1749,14856,1882,14685,1886,14506,1783,14324,1608,13996,1398,13702,1183]),Sr=null;function s2(){return Sr===null&&(Sr=new Qu(r2,16,16,bs,tr),Sr.name="DFG_LUT",Sr.minFilter=li,Sr.magFilter=li,Sr.wrapS=yr,Sr.wrapT=yr,Sr.generateMipmaps=!1,Sr.needsUpdate=!0),Sr}var cf=class{constructor(e={}){let{canvas:t=db(),context:i=null,depth:r=!0,stencil:s=!1,alpha:o=!1,antialias:a=!1,premultipliedAlpha:l=!0,preserveDrawingBuffer:c=!1,powerPreference:u="default",failIfMajorPerformanceCaveat:h=!1,reversedDepthBuffer:f=!1,outputBufferType:d=di}=e;this.isWebGLRenderer=!0;let p;if(i!==null){if(typeof WebGLRenderingContext<"u"&&i instanceof WebGLRenderingContext)throw new Error("THREE.WebGLRenderer: WebGL 1 is not supported since r163.");p=i.getContextAttributes().alpha}else p=o;let x=d,m=new Set([Th,Ah,wh]),g=new Set([di,Qi,ua,$s,Mh,Eh]),v=new Uint32Array(4),T=new Int32Array(4),M={textures:[],min:[],max:[],resolution:[]},R=null,w=null,y=[],A=[],k=null;this.domElement=t,this.debug={checkShaderErrors:!0,diagnostics:{keywords:!1},onShaderError:null},this.autoClear=!0,this.autoClearColor=!0,this.autoClearDepth=!0,this.autoClearStencil=!0,this.sortObjects=!0,this.clippingPlanes=[],this.localClippingEnabled=!1,this.toneMapping=br,this.toneMappingExposure=1,this.transmissionResolutionScale=1;let D=this,L=!1,H=null,z=null,N=null,F=null;this._outputColorSpace=wi;let Z=0,V=0,le=null,q=-1,Q=null,ie=new jt,fe=new jt,he=null,ee=new ft(0),ge=0,ye=t.width,xe=t.height,_e=1,ze=null,$e=null,Fe=new jt(0,0,ye,xe),st=new jt(0,0,ye,xe),ct=!1,ot=new ps,qt=new eh,Gt=!1,hn=!1,Ot=new Ht,Pn=new Y,St=new jt,En={background:null,fog:null,environment:null,overrideMaterial:null,isScene:!0},tn=!1;function fn(){return le===null?_e:1}let O=i;function Ce(E,B){return t.getContext(E,B)}let Ze,lt,we,Bt,He,Ye,I,b,X,ue,oe,be,Se,te,re,pe,U,se,ne,Ae,ve,Ee,We;try{let E={alpha:!0,depth:r,stencil:s,antialias:a,premultipliedAlpha:l,preserveDrawingBuffer:c,powerPreference:u,failIfMajorPerformanceCaveat:h};if("setAttribute"in t&&t.setAttribute("data-engine",`three.js r${"187"}`),t.addEventListener("webglcontextlost",ke,!1),t.addEventListener("webglcontextrestored",Qe,!1),t.addEventListener("webglcontextcreationerror",Ie,!1),O===null){let B="webgl2";if(O=Ce(B,E),O===null)throw Ce(B)?new Error("THREE.WebGLRenderer: Error creating WebGL context with your selected attributes."):new Error("THREE.WebGLRenderer: Error creating WebGL context.")}je()}catch(E){throw t.removeEventListener("webglcontextlost",ke,!1),t.removeEventListener("webglcontextrestored",Qe,!1),t.removeEventListener("webglcontextcreationerror",Ie,!1),nt("WebGLRenderer: "+E.message),E}function je(){Ze=new gC(O),Ze.init(),ve=new jN(O,Ze),lt=new sC(O,Ze,e,ve),we=new qN(O,Ze),lt.reversedDepthBuffer&&f&&we.buffers.depth.setReversed(!0),z=O.createFramebuffer(),N=O.createFramebuffer(),F=O.createFramebuffer(),Bt=new xC(O),He=new ON,Ye=new JN(O,Ze,we,He,lt,ve,Bt),I=new mC(D),b=new bT(O),Ee=new iC(O,b),X=new yC(O,b,Bt,Ee),ue=new bC(O,X,b,Ee,Bt),se=new vC(O,lt,Ye),re=new oC(He),oe=new UN(D,I,Ze,lt,Ee,re),be=new n2(D,He),Se=new BN,te=new WN(Ze),U=new nC(D,I,we,ue,p,l),pe=new $N(D,ue,lt),We=new i2(O,Bt,lt,we),ne=new rC(O,Ze,Bt),Ae=new _C(O,Ze,Bt),Bt.programs=oe.programs,D.capabilities=lt,D.extensions=Ze,D.properties=He,D.renderLists=Se,D.shadowMap=pe,D.state=we,D.info=Bt}x!==di&&(k=new MC(x,t.width,t.height,a,r,s));let ce=new Ym(D,O);this.xr=ce,this.getContext=function(){return O},this.getContextAttributes=function(){return O.getContextAttributes()},this.forceContextLoss=function(){let E=Ze.get("WEBGL_lose_context");E&&E.loseContext()},this.forceContextRestore=function(){let E=Ze.get("WEBGL_lose_context");E&&E.restoreContext()},this.getPixelRatio=function(){return _e},this.setPixelRatio=function(E){E!==void 0&&(_e=E,this.setSize(ye,xe,!1))},this.getSize=function(E){return E.set(ye,xe)},this.setSize=function(E,B,j=!0){if(ce.isPresenting){Ke("WebGLRenderer: Can't change size while VR device is presenting.");return}ye=E,xe=B,t.width=Math.floor(E*_e),t.height=Math.floor(B*_e),j===!0&&(t.style.width=E+"px",t.style.height=B+"px"),k!==null&&k.setSize(t.width,t.height),this.setViewport(0,0,E,B)},this.getDrawingBufferSize=function(E){return E.set(ye*_e,xe*_e).floor()},this.setDrawingBufferSize=function(E,B,j){ye=E,xe=B,_e=j,t.width=Math.floor(E*j),t.height=Math.floor(B*j),this.setViewport(0,0,E,B)},this.setEffects=function(E){if(x===di){nt("WebGLRenderer: setEffects() requires outputBufferType set to HalfFloatType or FloatType.");return}if(E){for(let B=0;B<E.length;B++)if(E[B].isOutputPass===!0){Ke("WebGLRenderer: OutputPass is not needed in setEffects(). Tone mapping and color space conversion are applied automatically.");break}}k.setEffects(E||[])},this.getCurrentViewport=function(E){return E.copy(ie)},this.getViewport=function(E){return E.copy(Fe)},this.setViewport=function(E,B,j,K){E.isVector4?Fe.set(E.x,E.y,E.z,E.w):Fe.set(E,B,j,K),we.viewport(ie.copy(Fe).multiplyScalar(fn()).round())},this.getScissor=function(E){return E.copy(st)},this.setScissor=function(E,B,j,K){E.isVector4?st.set(E.x,E.y,E.z,E.w):st.set(E,B,j,K),we.scissor(fe.copy(st).multiplyScalar(fn()).round())},this.getScissorTest=function(){return ct},this.setScissorTest=function(E){we.setScissorTest(ct=E)},this.setOpaqueSort=function(E){ze=E},this.setTransparentSort=function(E){$e=E},this.getClearColor=function(E){return E.copy(U.getClearColor())},this.setClearColor=function(){U.setClearColor(...arguments)},this.getClearAlpha=function(){return U.getClearAlpha()},this.setClearAlpha=function(){U.setClearAlpha(...arguments)},this.clear=function(E=!0,B=!0,j=!0){let K=0;if(E){let $=!1;if(le!==null){let Te=le.texture.format;$=m.has(Te)}if($){let Te=le.texture.type,Ne=g.has(Te),Re=U.getClearColor(),Pe=U.getClearAlpha(),Ge=Re.r,tt=Re.g,pt=Re.b;Ne?(v[0]=Ge,v[1]=tt,v[2]=pt,v[3]=Pe,O.clearBufferuiv(O.COLOR,0,v)):(T[0]=Ge,T[1]=tt,T[2]=pt,T[3]=Pe,O.clearBufferiv(O.COLOR,0,T))}else K|=O.COLOR_BUFFER_BIT}B&&(K|=O.DEPTH_BUFFER_BIT,this.state.buffers.depth.setMask(!0)),j&&(K|=O.STENCIL_BUFFER_BIT,this.state.buffers.stencil.setMask(4294967295)),K!==0&&O.clear(K)},this.clearColor=function(){this.clear(!0,!1,!1)},this.clearDepth=function(){this.clear(!1,!0,!1)},this.clearStencil=function(){this.clear(!1,!1,!0)},this.setNodesHandler=function(E){E.setRenderer(this),H=E},this.dispose=function(){t.removeEventListener("webglcontextlost",ke,!1),t.removeEventListener("webglcontextrestored",Qe,!1),t.removeEventListener("webglcontextcreationerror",Ie,!1),U.dispose(),Se.dispose(),te.dispose(),Ye.dispose(),He.dispose(),I.dispose(),ue.dispose(),X.dispose(),Ee.dispose(),We.dispose(),oe.dispose(),ce.dispose(),ce.removeEventListener("sessionstart",Yl),ce.removeEventListener("sessionend",ir),Er.stop()};function ke(E){E.preventDefault(),Rm("WebGLRenderer: Context Lost."),L=!0}function Qe(){Rm("WebGLRenderer: Context Restored."),L=!1;let E=Bt.autoReset,B=pe.enabled,j=pe.autoUpdate,K=pe.needsUpdate,$=pe.type;je(),Bt.autoReset=E,pe.enabled=B,pe.autoUpdate=j,pe.needsUpdate=K,pe.type=$}function Ie(E){nt("WebGLRenderer: A WebGL context could not be created. Reason: ",E.statusMessage)}function ut(E){let B=E.target;B.removeEventListener("dispose",ut),Wt(B)}function Wt(E){jn(E),He.remove(E)}function jn(E){let B=He.get(E).programs;B!==void 0&&(B.forEach(function(j){oe.releaseProgram(j)}),E.isShaderMaterial&&oe.releaseShaderCache(E))}this.renderBufferDirect=function(E,B,j,K,$,Te){B===null&&(B=En);let Ne=$.isMesh&&$.matrixWorld.determinantAffine()<0,Re=ya(E,B,j,K,$);we.setMaterial(K,Ne);let Pe=j.index,Ge=1;if(K.wireframe===!0){if(Pe=X.getWireframeAttribute(j),Pe===void 0)return;Ge=2}let tt=j.drawRange,pt=j.attributes.position,Ve=tt.start*Ge,mt=(tt.start+tt.count)*Ge;Te!==null&&(Ve=Math.max(Ve,Te.start*Ge),mt=Math.min(mt,(Te.start+Te.count)*Ge)),Pe!==null?(Ve=Math.max(Ve,0),mt=Math.min(mt,Pe.count)):pt!=null&&(Ve=Math.max(Ve,0),mt=Math.min(mt,pt.count));let Qt=mt-Ve;if(Qt<0||Qt===1/0)return;Ee.setup($,K,Re,j,Pe);let Pt,Lt=ne;if(Pe!==null&&(Pt=b.get(Pe),Lt=Ae,Lt.setIndex(Pt)),$.isMesh)K.wireframe===!0?(we.setLineWidth(K.wireframeLinewidth*fn()),Lt.setMode(O.LINES)):Lt.setMode(O.TRIANGLES);else if($.isLine){let wn=K.linewidth;wn===void 0&&(wn=1),we.setLineWidth(wn*fn()),$.isLineSegments?Lt.setMode(O.LINES):$.isLineLoop?Lt.setMode(O.LINE_LOOP):Lt.setMode(O.LINE_STRIP)}else $.isPoints?Lt.setMode(O.POINTS):$.isSprite&&Lt.setMode(O.TRIANGLES);if($.isBatchedMesh)if(Ze.get("WEBGL_multi_draw"))Lt.renderMultiDraw($._multiDrawStarts,$._multiDrawCounts,$._multiDrawCount);else{let wn=$._multiDrawStarts,Oe=$._multiDrawCounts,dn=$._multiDrawCount,_t=Pe?b.get(Pe).bytesPerElement:1,Ar=He.get(K).currentProgram.getUniforms();for(let pn=0;pn<dn;pn++)Ar.setValue(O,"_gl_DrawID",pn),Lt.render(wn[pn]/_t,Oe[pn])}else if($.isInstancedMesh)Lt.renderInstances(Ve,Qt,$.count);else if(j.isInstancedBufferGeometry){let wn=j._maxInstanceCount!==void 0?j._maxInstanceCount:1/0,Oe=Math.min(j.instanceCount,wn);Lt.renderInstances(Ve,Qt,Oe)}else Lt.render(Ve,Qt)};function pa(E,B,j,K){H!==null&&E.isNodeMaterial&&H.setObject(K,E),Gt===!0&&re.setState(E,j,!1),E.transparent===!0&&E.side===Fi&&E.forceSinglePass===!1?(E.side=ui,E.needsUpdate=!0,rr(E,B,K),E.side=vs,E.needsUpdate=!0,rr(E,B,K),E.side=Fi):rr(E,B,K)}this.compile=function(E,B,j=null){j===null&&(j=E),H!==null&&H.renderStart(E,B,j),w=te.get(j),w.init(B),A.push(w),j.traverseVisible(function($){$.isLight&&$.layers.test(B.layers)&&(w.pushLight($),$.castShadow&&w.pushShadow($))}),E!==j&&E.traverseVisible(function($){$.isLight&&$.layers.test(B.layers)&&(w.pushLight($),$.castShadow&&w.pushShadow($))}),w.setupLights(),H!==null&&H.updateLights(w.state.lightsArray),hn=this.localClippingEnabled,Gt=re.init(this.clippingPlanes,hn),Gt===!0&&re.setGlobalState(this.clippingPlanes,B),H!==null&&pe.render(w.state.shadowsArray,j,B);let K=new Set;return E.traverse(function($){if(!($.isMesh||$.isPoints||$.isLine||$.isSprite))return;let Te=$.material;if(Te)if(Array.isArray(Te))for(let Ne=0;Ne<Te.length;Ne++){let Re=Te[Ne];pa(Re,j,B,$),K.add(Re)}else pa(Te,j,B,$),K.add(Te)}),w=A.pop(),H!==null&&H.renderEnd(),K},this.compileAsync=function(E,B,j=null){let K=this.compile(E,B,j);return new Promise($=>{function Te(){if(K.forEach(function(Ne){let Pe=He.get(Ne).currentProgram;(Pe===void 0||Pe.isReady())&&K.delete(Ne)}),K.size===0){$(E);return}setTimeout(Te,10)}Ze.get("KHR_parallel_shader_compile")!==null?Te():setTimeout(Te,10)})};let js=null;function yf(E){js&&js(E)}function Yl(){Er.stop()}function ir(){Er.start()}let Er=new Wb;Er.setAnimationLoop(yf),typeof self<"u"&&Er.setContext(self),this.setAnimationLoop=function(E){js=E,ce.setAnimationLoop(E),E===null?Er.stop():Er.start()},ce.addEventListener("sessionstart",Yl),ce.addEventListener("sessionend",ir),this.render=function(E,B){if(B!==void 0&&B.isCamera!==!0){nt("WebGLRenderer.render: camera is not an instance of THREE.Camera.");return}if(L===!0)return;H!==null&&H.renderStart(E,B);let j=ce.enabled===!0&&ce.isPresenting===!0,K=k!==null&&(le===null||j)&&k.begin(D,le);if(E.matrixWorldAutoUpdate===!0&&E.updateMatrixWorld(),B.parent===null&&B.matrixWorldAutoUpdate===!0&&B.updateMatrixWorld(),ce.enabled===!0&&ce.isPresenting===!0&&(k===null||k.isCompositing()===!1)&&(ce.cameraAutoUpdate===!0&&ce.updateCamera(B),B=ce.getCamera()),E.isScene===!0&&E.onBeforeRender(D,E,B,le),w=te.get(E,A.length),w.init(B),w.state.textureUnits=Ye.getTextureUnits(),A.push(w),Ot.multiplyMatrices(B.projectionMatrix,B.matrixWorldInverse),B.isArrayCamera?qt.setFromArrayCamera(B):ot.setFromProjectionMatrix(Ot,Oi,B.reversedDepth),hn=this.localClippingEnabled,Gt=re.init(this.clippingPlanes,hn),R=Se.get(E,y.length),R.init(),y.push(R),this.info.render.frame++,ce.enabled===!0&&ce.isPresenting===!0){let Ne=D.xr.getDepthSensingMesh();Ne!==null&&wr(Ne,B,-1/0,D.sortObjects)}wr(E,B,0,D.sortObjects),R.finish(),H!==null&&H.updateLights(w.state.lightsArray),D.sortObjects===!0&&R.sort(ze,$e),tn=ce.enabled===!1||ce.isPresenting===!1||ce.hasDepthSensing()===!1,tn&&U.addToRenderList(R,E),this.info.autoReset===!0&&this.info.reset(),Gt===!0&&re.beginShadows();let $=w.state.shadowsArray;if(pe.render($,E,B),Gt===!0&&re.endShadows(),(K&&k.hasRenderPass())===!1){let Ne=R.opaque,Re=R.transmissive;if(w.setupLights(),B.isArrayCamera){let Pe=B.cameras;if(Re.length>0)for(let Ge=0,tt=Pe.length;Ge<tt;Ge++){let pt=Pe[Ge];Bi(Ne,Re,E,pt)}tn&&U.render(E);for(let Ge=0,tt=Pe.length;Ge<tt;Ge++){let pt=Pe[Ge];ma(R,E,pt,pt.viewport)}}else Re.length>0&&Bi(Ne,Re,E,B),tn&&U.render(E),ma(R,E,B)}le!==null&&V===0&&(Ye.updateMultisampleRenderTarget(le),Ye.updateRenderTargetMipmap(le)),K&&k.end(D),E.isScene===!0&&E.onAfterRender(D,E,B),Ee.resetDefaultState(),q=-1,Q=null,A.pop(),A.length>0?(w=A[A.length-1],Ye.setTextureUnits(w.state.textureUnits),Gt===!0&&re.setGlobalState(D.clippingPlanes,w.state.camera)):w=null,y.pop(),y.length>0?R=y[y.length-1]:R=null,H!==null&&H.renderEnd()};function wr(E,B,j,K){if(E.visible===!1)return;if(E.layers.test(B.layers)){if(E.isGroup)j=E.renderOrder;else if(E.isLOD)E.autoUpdate===!0&&E.update(B);else if(E.isLight)w.pushLight(E),E.castShadow&&w.pushShadow(E);else if(E.isSprite){let Ne=B.isArrayCamera?qt:ot;if(!E.frustumCulled||E.intersectsFrustum(Ne)){K&&St.setFromMatrixPosition(E.matrixWorld).applyMatrix4(Ot);let Re=ue.update(E),Pe=E.material;Pe.visible&&R.push(E,Re,Pe,j,St.z,null,B)}}else if(E.isMesh||E.isLine||E.isPoints){let Ne=B.isArrayCamera?qt:ot;if(!E.frustumCulled||E.intersectsFrustum(Ne)){let Re=ue.update(E),Pe=E.material;if(K&&(E.boundingSphere!==void 0?(E.boundingSphere===null&&E.computeBoundingSphere(),St.copy(E.boundingSphere.center)):(Re.boundingSphere===null&&Re.computeBoundingSphere(),St.copy(Re.boundingSphere.center)),St.applyMatrix4(E.matrixWorld).applyMatrix4(Ot)),Array.isArray(Pe)){let Ge=Re.groups;for(let tt=0,pt=Ge.length;tt<pt;tt++){let Ve=Ge[tt],mt=Pe[Ve.materialIndex];mt&&mt.visible&&R.push(E,Re,mt,j,St.z,Ve,B)}}else Pe.visible&&R.push(E,Re,Pe,j,St.z,null,B)}}}let Te=E.children;for(let Ne=0,Re=Te.length;Ne<Re;Ne++)wr(Te[Ne],B,j,K)}function ma(E,B,j,K){let{opaque:$,transmissive:Te,transparent:Ne}=E;w.setupLightsView(j),Gt===!0&&re.setGlobalState(D.clippingPlanes,j),K&&we.viewport(ie.copy(K)),$.length>0&&nn($,B,j),Te.length>0&&nn(Te,B,j),Ne.length>0&&nn(Ne,B,j),we.buffers.depth.setTest(!0),we.buffers.depth.setMask(!0),we.buffers.color.setMask(!0),we.setPolygonOffset(!1)}function Bi(E,B,j,K){if((j.isScene===!0?j.overrideMaterial:null)!==null)return;if(w.state.transmissionRenderTarget[K.id]===void 0){let Ve=Ze.has("EXT_color_buffer_half_float")||Ze.has("EXT_color_buffer_float");w.state.transmissionRenderTarget[K.id]=new Ai(1,1,{generateMipmaps:!0,type:Ve?tr:di,minFilter:Xr,samples:Math.max(4,lt.samples),stencilBuffer:s,resolveDepthBuffer:!1,resolveStencilBuffer:!1,storeMultisampledDepthBuffer:!1,storeMultisampledStencilBuffer:!1,colorSpace:vt.workingColorSpace})}let Te=w.state.transmissionRenderTarget[K.id],Ne=K.viewport||ie;Te.setSize(Ne.z*D.transmissionResolutionScale,Ne.w*D.transmissionResolutionScale);let Re=D.getRenderTarget(),Pe=D.getActiveCubeFace(),Ge=D.getActiveMipmapLevel();D.setRenderTarget(Te),D.getClearColor(ee),ge=D.getClearAlpha(),ge<1&&D.setClearColor(16777215,.5),D.clear(),tn&&U.render(j);let tt=D.toneMapping;D.toneMapping=br;let pt=K.viewport;if(K.viewport!==void 0&&(K.viewport=void 0),w.setupLightsView(K),Gt===!0&&re.setGlobalState(D.clippingPlanes,K),nn(E,j,K),Ye.updateMultisampleRenderTarget(Te),Ye.updateRenderTargetMipmap(Te),Ze.has("WEBGL_multisampled_render_to_texture")===!1){let Ve=!1;for(let mt=0,Qt=B.length;mt<Qt;mt++){let Pt=B[mt],{object:Lt,geometry:wn,material:Oe,group:dn}=Pt;if(Oe.side===Fi&&Lt.layers.test(K.layers)){let _t=Oe.side;Oe.side=ui,Oe.needsUpdate=!0,ln(Lt,j,K,wn,Oe,dn),Oe.side=_t,Oe.needsUpdate=!0,Ve=!0}}Ve===!0&&(Ye.updateMultisampleRenderTarget(Te),Ye.updateRenderTargetMipmap(Te))}D.setRenderTarget(Re,Pe,Ge),D.setClearColor(ee,ge),pt!==void 0&&(K.viewport=pt),D.toneMapping=tt}function nn(E,B,j){let K=B.isScene===!0?B.overrideMaterial:null;for(let $=0,Te=E.length;$<Te;$++){let Ne=E[$],{object:Re,geometry:Pe,group:Ge}=Ne,tt=Ne.material;tt.allowOverride===!0&&K!==null&&(tt=K),Re.layers.test(j.layers)&&ln(Re,B,j,Pe,tt,Ge)}}function ln(E,B,j,K,$,Te){H!==null&&$.isNodeMaterial&&H.setObject(E,$),E.onBeforeRender(D,B,j,K,$,Te),E.modelViewMatrix.multiplyMatrices(j.matrixWorldInverse,E.matrixWorld),E.normalMatrix.getNormalMatrix(E.modelViewMatrix),$.onBeforeRender(D,B,j,K,E,Te),$.transparent===!0&&$.side===Fi&&$.forceSinglePass===!1?($.side=ui,$.needsUpdate=!0,D.renderBufferDirect(j,B,K,$,E,Te),$.side=vs,$.needsUpdate=!0,D.renderBufferDirect(j,B,K,$,E,Te),$.side=Fi):D.renderBufferDirect(j,B,K,$,E,Te),E.onAfterRender(D,B,j,K,$,Te)}function cn(E){let B=0;for(let j of E)j.texture!==null&&B++;return B}function rr(E,B,j){B.isScene!==!0&&(B=En);let K=He.get(E),$=w.state.lights,Te=w.state.shadowsArray,Ne=$.state.version,Re=oe.getParameters(E,$.state,Te,B,j,w.state.lightProbeGridArray),Pe=oe.getProgramCacheKey(Re),Ge=K.programs;K.environment=E.isMeshStandardMaterial||E.isMeshLambertMaterial||E.isMeshPhongMaterial?B.environment:null,K.fog=B.fog;let tt=E.isMeshStandardMaterial||E.isMeshLambertMaterial&&!E.envMap||E.isMeshPhongMaterial&&!E.envMap;K.envMap=I.get(E.envMap||K.environment,tt),K.envMapRotation=K.environment!==null&&E.envMap===null?B.environmentRotation:E.envMapRotation,Ge===void 0&&(E.addEventListener("dispose",ut),Ge=new Map,K.programs=Ge,K.programVariants=new Map);let pt=Ge.get(Pe);if(pt!==void 0){if(K.currentProgram===pt&&K.lightsStateVersion===Ne)return ga(E,Re),pt}else Re.uniforms=oe.getUniforms(E),H!==null&&E.isNodeMaterial&&H.build(E,j,Re),E.onBeforeCompile(Re,D),pt=oe.acquireProgram(Re,Pe),Ge.set(Pe,pt),K.uniforms=Re.uniforms;let Ve=K.uniforms;return(!E.isShaderMaterial&&!E.isRawShaderMaterial||E.clipping===!0)&&(Ve.clippingPlanes=re.uniform),ga(E,Re),K.needsLights=$r(E),K.lightsStateVersion=Ne,K.needsLights&&(Ve.ambientLightColor.value=$.state.ambient,Ve.lightProbe.value=$.state.probe,Ve.sunLights.value=$.state.sun,Ve.sunLightShadows.value=$.state.sunShadow,Ve.directionalLights.value=$.state.directional,Ve.directionalLightShadows.value=$.state.directionalShadow,Ve.spotLights.value=$.state.spot,Ve.spotLightShadows.value=$.state.spotShadow,Ve.rectAreaLights.value=$.state.rectArea,Ve.ltc_1.value=$.state.rectAreaLTC1,Ve.ltc_2.value=$.state.rectAreaLTC2,Ve.pointLights.value=$.state.point,Ve.pointLightShadows.value=$.state.pointShadow,Ve.hemisphereLights.value=$.state.hemi,Ve.sunShadowMatrix.value=$.state.sunShadowMatrix,Ve.sunShadowCascade.value=$.state.sunShadowCascade,Ve.directionalShadowMatrix.value=$.state.directionalShadowMatrix,Ve.spotLightMatrix.value=$.state.spotLightMatrix,Ve.spotLightMap.value=$.state.spotLightMap,Ve.pointShadowMatrix.value=$.state.pointShadowMatrix),K.numLightProbeGrids=cn(w.state.lightProbeGridArray),K.currentProgram=pt,K.uniformsList=null,pt}function mi(E,B,j,K,$){let Te=He.get(E),Ne=Te.currentProgram.id+","+K+","+$,Re=Te.programVariants.get(Ne);return Re===void 0?(Re=rr(E,B,j),Te.programVariants.set(Ne,Re)):(Te.currentProgram=Re,Te.uniformsList=null,Te.outputColorSpace=K,Te.toneMapping=$),Re}function Kr(E){if(E.uniformsList===null){let B=E.currentProgram.getUniforms();E.uniformsList=fa.seqWithValue(B.seq,E.uniforms)}return E.uniformsList}function ga(E,B){let j=He.get(E);j.outputColorSpace=B.outputColorSpace,j.batching=B.batching,j.batchingColor=B.batchingColor,j.instancing=B.instancing,j.instancingColor=B.instancingColor,j.instancingMorph=B.instancingMorph,j.skinning=B.skinning,j.morphTargets=B.morphTargets,j.morphNormals=B.morphNormals,j.morphColors=B.morphColors,j.morphTargetsCount=B.morphTargetsCount,j.numClippingPlanes=B.numClippingPlanes,j.numIntersection=B.numClipIntersection,j.vertexAlphas=B.vertexAlphas,j.vertexTangents=B.vertexTangents,j.toneMapping=B.toneMapping}function ya(E,B,j,K,$){B.isScene!==!0&&(B=En),Ye.resetTextureUnits();let Te=B.fog,Ne=K.isMeshStandardMaterial||K.isMeshLambertMaterial||K.isMeshPhongMaterial?B.environment:null,Re=le===null?D.outputColorSpace:le.isXRRenderTarget===!0?le.texture.colorSpace:vt.workingColorSpace,Pe=K.isMeshStandardMaterial||K.isMeshLambertMaterial&&!K.envMap||K.isMeshPhongMaterial&&!K.envMap,Ge=I.get(K.envMap||Ne,Pe),tt=K.vertexColors===!0&&!!j.attributes.color&&j.attributes.color.itemSize===4,pt=!!j.attributes.tangent&&(!!K.normalMap||K.anisotropy>0),Ve=!!j.morphAttributes.position,mt=!!j.morphAttributes.normal,Qt=!!j.morphAttributes.color,Pt=br;K.toneMapped&&(le===null||le.isXRRenderTarget===!0)&&(Pt=D.toneMapping);let Lt=j.morphAttributes.position||j.morphAttributes.normal||j.morphAttributes.color,wn=Lt!==void 0?Lt.length:0,Oe=He.get(K),dn=w.state.lights;if(Gt===!0&&(hn===!0||E!==Q)){let Dt=E===Q&&K.id===q;re.setState(K,E,Dt)}let _t=!1,Ar=!1;K.version===Oe.__version?Oe.needsLights&&Oe.lightsStateVersion!==dn.state.version||$.isBatchedMesh&&Oe.batching===!1||!$.isBatchedMesh&&Oe.batching===!0||$.isBatchedMesh&&Oe.batchingColor===!0&&$._colorsTexture===null||$.isBatchedMesh&&Oe.batchingColor===!1&&$._colorsTexture!==null||$.isInstancedMesh&&Oe.instancing===!1||!$.isInstancedMesh&&Oe.instancing===!0||$.isSkinnedMesh&&Oe.skinning===!1||!$.isSkinnedMesh&&Oe.skinning===!0||$.isInstancedMesh&&Oe.instancingColor===!0&&$.instanceColor===null||$.isInstancedMesh&&Oe.instancingColor===!1&&$.instanceColor!==null||$.isInstancedMesh&&Oe.instancingMorph===!0&&$.morphTexture===null||$.isInstancedMesh&&Oe.instancingMorph===!1&&$.morphTexture!==null||Oe.envMap!==Ge||K.fog===!0&&Oe.fog!==Te||Oe.numClippingPlanes!==void 0&&(Oe.numClippingPlanes!==re.numPlanes||Oe.numIntersection!==re.numIntersection)||Oe.vertexAlphas!==tt||Oe.vertexTangents!==pt||Oe.morphTargets!==Ve||Oe.morphNormals!==mt||Oe.morphColors!==Qt||Oe.morphTargetsCount!==wn||Oe.numLightProbeGrids!==cn(w.state.lightProbeGridArray)?_t=!0:(Oe.outputColorSpace!==Re||Oe.toneMapping!==Pt)&&(Ar=!0):(_t=!0,Oe.__version=K.version);let pn=Oe.currentProgram;(_t===!0||Ar===!0)&&(pn=Ar===!0?mi(K,B,$,Re,Pt):rr(K,B,$),H&&K.isNodeMaterial&&H.onUpdateProgram(K,pn,Oe));let to=!1,sr=!1,Tr=!1,ht=pn.getUniforms(),rn=Oe.uniforms;if(we.useProgram(pn.program)&&(to=!0,sr=!0,Tr=!0),K.id!==q&&(q=K.id,sr=!0),to||Q!==E){we.buffers.depth.getReversed()&&E.reversedDepth!==!0&&(E._reversedDepth=!0,E.updateProjectionMatrix()),ht.setValue(O,"projectionMatrix",E.projectionMatrix),ht.setValue(O,"viewMatrix",E.matrixWorldInverse);let mn=ht.map.cameraPosition;mn!==void 0&&mn.setValue(O,Pn.setFromMatrixPosition(E.matrixWorld)),lt.logarithmicDepthBuffer&&ht.setValue(O,"logDepthBufFC",2/(Math.log(E.far+1)/Math.LN2)),(K.isMeshPhongMaterial||K.isMeshToonMaterial||K.isMeshLambertMaterial||K.isMeshBasicMaterial||K.isMeshStandardMaterial||K.isShaderMaterial)&&ht.setValue(O,"isOrthographic",E.isOrthographicCamera===!0),Q!==E&&(Q=E,sr=!0,Tr=!0)}if(Oe.needsLights&&(dn.state.sunShadowMap.length>0&&ht.setValue(O,"sunShadowMap",dn.state.sunShadowMap,Ye),dn.state.directionalShadowMap.length>0&&ht.setValue(O,"directionalShadowMap",dn.state.directionalShadowMap,Ye),dn.state.spotShadowMap.length>0&&ht.setValue(O,"spotShadowMap",dn.state.spotShadowMap,Ye),dn.state.pointShadowMap.length>0&&ht.setValue(O,"pointShadowMap",dn.state.pointShadowMap,Ye)),$.isSkinnedMesh){ht.setOptional(O,$,"bindMatrix"),ht.setOptional(O,$,"bindMatrixInverse");let Dt=$.skeleton;Dt&&(Dt.boneTexture===null&&Dt.computeBoneTexture(),ht.setValue(O,"boneTexture",Dt.boneTexture,Ye))}$.isBatchedMesh&&(ht.setOptional(O,$,"batchingTexture"),ht.setValue(O,"batchingTexture",$._matricesTexture,Ye),ht.setOptional(O,$,"batchingIdTexture"),ht.setValue(O,"batchingIdTexture",$._indirectTexture,Ye),ht.setOptional(O,$,"batchingColorTexture"),$._colorsTexture!==null&&ht.setValue(O,"batchingColorTexture",$._colorsTexture,Ye));let Qn=j.morphAttributes;if((Qn.position!==void 0||Qn.normal!==void 0||Qn.color!==void 0)&&se.update($,j,pn),(sr||Oe.receiveShadow!==$.receiveShadow)&&(Oe.receiveShadow=$.receiveShadow,ht.setValue(O,"receiveShadow",$.receiveShadow)),(K.isMeshStandardMaterial||K.isMeshLambertMaterial||K.isMeshPhongMaterial)&&K.envMap===null&&B.environment!==null&&(rn.envMapIntensity.value=B.environmentIntensity),rn.dfgLUT!==void 0&&(rn.dfgLUT.value=s2()),sr){if(ht.setValue(O,"toneMappingExposure",D.toneMappingExposure),Oe.needsLights&&Qs(rn,Tr),Te&&K.fog===!0&&be.refreshFogUniforms(rn,Te),be.refreshMaterialUniforms(rn,K,_e,xe,w.state.transmissionRenderTarget[E.id]),Oe.needsLights&&Oe.numLightProbeGrids>0){let Dt=M,mn=0;for(let Hn of w.state.lightProbeGridArray)Hn.texture!==null&&(Dt.textures[mn]=Hn.texture,Dt.min[mn]=Hn.boundingBox.min,Dt.max[mn]=Hn.boundingBox.max,Dt.resolution[mn]=Hn.resolution,mn++);for(let Hn in Dt)Dt[Hn].length=mn;rn.probesSH.value=Dt.textures,rn.probesMin.value=Dt.min,rn.probesMax.value=Dt.max,rn.probesResolution.value=Dt.resolution}fa.upload(O,Kr(Oe),rn,Ye)}if(K.isShaderMaterial&&K.uniformsNeedUpdate===!0&&(fa.upload(O,Kr(Oe),rn,Ye),K.uniformsNeedUpdate=!1),K.isSpriteMaterial&&ht.setValue(O,"center",$.center),ht.setValue(O,"modelViewMatrix",$.modelViewMatrix),ht.setValue(O,"normalMatrix",$.normalMatrix),ht.setValue(O,"modelMatrix",$.matrixWorld),K.uniformsGroups!==void 0){let Dt=K.uniformsGroups;for(let mn=0,Hn=Dt.length;mn<Hn;mn++){let Zl=Dt[mn];We.update(Zl,pn),We.bind(Zl,pn)}}return pn}function Qs(E,B){E.ambientLightColor.needsUpdate=B,E.lightProbe.needsUpdate=B,E.sunLights.needsUpdate=B,E.sunLightShadows.needsUpdate=B,E.directionalLights.needsUpdate=B,E.directionalLightShadows.needsUpdate=B,E.pointLights.needsUpdate=B,E.pointLightShadows.needsUpdate=B,E.spotLights.needsUpdate=B,E.spotLightShadows.needsUpdate=B,E.rectAreaLights.needsUpdate=B,E.hemisphereLights.needsUpdate=B}function $r(E){return E.isMeshLambertMaterial||E.isMeshToonMaterial||E.isMeshPhongMaterial||E.isMeshStandardMaterial||E.isShadowMaterial||E.isShaderMaterial&&E.lights===!0}this.getActiveCubeFace=function(){return Z},this.getActiveMipmapLevel=function(){return V},this.getRenderTarget=function(){return le},this.setRenderTargetTextures=function(E,B,j){let K=He.get(E);K.__autoAllocateDepthBuffer=E.resolveDepthBuffer===!1,K.__autoAllocateDepthBuffer===!1&&(K.__useRenderToTexture=!1),He.get(E.texture).__webglTexture=B,He.get(E.depthTexture).__webglTexture=K.__autoAllocateDepthBuffer?void 0:j,K.__hasExternalTextures=!0},this.setRenderTargetFramebuffer=function(E,B){let j=He.get(E);j.__webglFramebuffer=B,j.__useDefaultFramebuffer=B===void 0},this.setRenderTarget=function(E,B=0,j=0){le=E,Z=B,V=j;let K=null,$=!1,Te=!1;if(E){let Re=He.get(E);if(Re.__useDefaultFramebuffer!==void 0){we.bindFramebuffer(O.FRAMEBUFFER,Re.__webglFramebuffer),ie.copy(E.viewport),fe.copy(E.scissor),he=E.scissorTest,we.viewport(ie),we.scissor(fe),we.setScissorTest(he),q=-1;return}else if(Re.__webglFramebuffer===void 0)Ye.setupRenderTarget(E);else if(Re.__hasExternalTextures)Ye.rebindTextures(E,He.get(E.texture).__webglTexture,He.get(E.depthTexture).__webglTexture);else if(E.depthBuffer){let tt=E.depthTexture;if(Re.__boundDepthTexture!==tt){if(tt!==null&&He.has(tt)&&(E.width!==tt.image.width||E.height!==tt.image.height))throw new Error("THREE.WebGLRenderer: Attached DepthTexture is initialized to the incorrect size.");Ye.setupDepthRenderbuffer(E)}}let Pe=E.texture;(Pe.isData3DTexture||Pe.isDataArrayTexture||Pe.isCompressedArrayTexture)&&(Te=!0);let Ge=He.get(E).__webglFramebuffer;E.isWebGLCubeRenderTarget?(Array.isArray(Ge[B])?K=Ge[B][j]:K=Ge[B],$=!0):E.samples>0&&Ye.useMultisampledRTT(E)===!1?K=He.get(E).__webglMultisampledFramebuffer:Array.isArray(Ge)?K=Ge[j]:K=Ge,ie.copy(E.viewport),fe.copy(E.scissor),he=E.scissorTest}else ie.copy(Fe).multiplyScalar(_e).floor(),fe.copy(st).multiplyScalar(_e).floor(),he=ct;if(j!==0&&(K=z),we.bindFramebuffer(O.FRAMEBUFFER,K)&&we.drawBuffers(E,K),we.viewport(ie),we.scissor(fe),we.setScissorTest(he),$){let Re=He.get(E.texture);O.framebufferTexture2D(O.FRAMEBUFFER,O.COLOR_ATTACHMENT0,O.TEXTURE_CUBE_MAP_POSITIVE_X+B,Re.__webglTexture,j)}else if(Te){let Re=B;for(let Pe=0;Pe<E.textures.length;Pe++){let Ge=He.get(E.textures[Pe]);O.framebufferTextureLayer(O.FRAMEBUFFER,O.COLOR_ATTACHMENT0+Pe,Ge.__webglTexture,j,Re)}}else if(E!==null&&j!==0){let Re=He.get(E.texture);O.framebufferTexture2D(O.FRAMEBUFFER,O.COLOR_ATTACHMENT0,O.TEXTURE_2D,Re.__webglTexture,j)}q=-1};function eo(E){let B=He.get(E);return(B.__readFormat!==E.format||B.__readType!==E.type)&&(B.__readFormat=E.format,B.__readType=E.type,B.__formatReadable=lt.textureFormatReadable(E.format),B.__typeReadable=lt.textureTypeReadable(E.type)),B}this.readRenderTargetPixels=function(E,B,j,K,$,Te,Ne,Re=0){if(!(E&&E.isWebGLRenderTarget)){nt("WebGLRenderer.readRenderTargetPixels: renderTarget is not THREE.WebGLRenderTarget.");return}let Pe=He.get(E).__webglFramebuffer;if(E.isWebGLCubeRenderTarget&&Ne!==void 0&&(Pe=Pe[Ne],Array.isArray(Pe)&&(Pe=Pe[0])),Pe){we.bindFramebuffer(O.FRAMEBUFFER,Pe);try{let Ge=E.textures[Re],tt=Ge.format,pt=Ge.type;E.textures.length>1&&O.readBuffer(O.COLOR_ATTACHMENT0+Re);let Ve=eo(Ge);if(Ve.__formatReadable===!1){nt("WebGLRenderer.readRenderTargetPixels: renderTarget is not in RGBA or implementation defined format.");return}if(Ve.__typeReadable===!1){nt("WebGLRenderer.readRenderTargetPixels: renderTarget is not in UnsignedByteType or implementation defined type.");return}B>=0&&B<=E.width-K&&j>=0&&j<=E.height-$&&O.readPixels(B,j,K,$,ve.convert(tt),ve.convert(pt),Te)}finally{let Ge=le!==null?He.get(le).__webglFramebuffer:null;we.bindFramebuffer(O.FRAMEBUFFER,Ge)}}},this.readRenderTargetPixelsAsync=async function(E,B,j,K,$,Te,Ne,Re=0){if(!(E&&E.isWebGLRenderTarget))throw new Error("THREE.WebGLRenderer.readRenderTargetPixels: renderTarget is not THREE.WebGLRenderTarget.");let Pe=He.get(E).__webglFramebuffer;if(E.isWebGLCubeRenderTarget&&Ne!==void 0&&(Pe=Pe[Ne],Array.isArray(Pe)&&(Pe=Pe[0])),Pe)if(B>=0&&B<=E.width-K&&j>=0&&j<=E.height-$){we.bindFramebuffer(O.FRAMEBUFFER,Pe);let Ge=E.textures[Re],tt=Ge.format,pt=Ge.type;E.textures.length>1&&O.readBuffer(O.COLOR_ATTACHMENT0+Re);let Ve=eo(Ge);if(Ve.__formatReadable===!1)throw new Error("THREE.WebGLRenderer.readRenderTargetPixelsAsync: renderTarget is not in RGBA or implementation defined format.");if(Ve.__typeReadable===!1)throw new Error("THREE.WebGLRenderer.readRenderTargetPixelsAsync: renderTarget is not in UnsignedByteType or implementation defined type.");let mt=O.createBuffer();O.bindBuffer(O.PIXEL_PACK_BUFFER,mt),O.bufferData(O.PIXEL_PACK_BUFFER,Te.byteLength,O.STREAM_READ),O.readPixels(B,j,K,$,ve.convert(tt),ve.convert(pt),0),O.bindBuffer(O.PIXEL_PACK_BUFFER,null);let Qt=le!==null?He.get(le).__webglFramebuffer:null;we.bindFramebuffer(O.FRAMEBUFFER,Qt);let Pt=O.fenceSync(O.SYNC_GPU_COMMANDS_COMPLETE,0);return O.flush(),await mb(O,Pt,4),O.bindBuffer(O.PIXEL_PACK_BUFFER,mt),O.getBufferSubData(O.PIXEL_PACK_BUFFER,0,Te),O.bindBuffer(O.PIXEL_PACK_BUFFER,null),O.deleteBuffer(mt),O.deleteSync(Pt),Te}else throw new Error("THREE.WebGLRenderer.readRenderTargetPixelsAsync: requested read bounds are out of range.")},this.copyFramebufferToTexture=function(E,B=null,j=0){let K=Math.pow(2,-j),$=Math.floor(E.image.width*K),Te=Math.floor(E.image.height*K),Ne=B!==null?B.x:0,Re=B!==null?B.y:0;Ye.setTexture2D(E,0),O.copyTexSubImage2D(O.TEXTURE_2D,j,0,0,Ne,Re,$,Te),we.unbindTexture()},this.copyTextureToTexture=function(E,B,j=null,K=null,$=0,Te=0){let Ne,Re,Pe,Ge,tt,pt,Ve,mt,Qt,Pt=E.isCompressedTexture?E.mipmaps[Te]:E.image;if(j!==null)Ne=j.max.x-j.min.x,Re=j.max.y-j.min.y,Pe=j.isBox3?j.max.z-j.min.z:1,Ge=j.min.x,tt=j.min.y,pt=j.isBox3?j.min.z:0;else{let ht=Math.pow(2,-$);Ne=Math.floor(Pt.width*ht),Re=Math.floor(Pt.height*ht),E.isDataArrayTexture?Pe=Pt.depth:E.isData3DTexture?Pe=Math.floor(Pt.depth*ht):Pe=1,Ge=0,tt=0,pt=0}K!==null?(Ve=K.x,mt=K.y,Qt=K.z):(Ve=0,mt=0,Qt=0);let Lt=ve.convert(B.format),wn=ve.convert(B.type),Oe;B.isData3DTexture?(Ye.setTexture3D(B,0),Oe=O.TEXTURE_3D):B.isDataArrayTexture||B.isCompressedArrayTexture?(Ye.setTexture2DArray(B,0),Oe=O.TEXTURE_2D_ARRAY):(Ye.setTexture2D(B,0),Oe=O.TEXTURE_2D),we.activeTexture(O.TEXTURE0),we.pixelStorei(O.UNPACK_FLIP_Y_WEBGL,B.flipY),we.pixelStorei(O.UNPACK_PREMULTIPLY_ALPHA_WEBGL,B.premultiplyAlpha),we.pixelStorei(O.UNPACK_ALIGNMENT,B.unpackAlignment);let dn=we.getParameter(O.UNPACK_ROW_LENGTH),_t=we.getParameter(O.UNPACK_IMAGE_HEIGHT),Ar=we.getParameter(O.UNPACK_SKIP_PIXELS),pn=we.getParameter(O.UNPACK_SKIP_ROWS),to=we.getParameter(O.UNPACK_SKIP_IMAGES);we.pixelStorei(O.UNPACK_ROW_LENGTH,Pt.width),we.pixelStorei(O.UNPACK_IMAGE_HEIGHT,Pt.height),we.pixelStorei(O.UNPACK_SKIP_PIXELS,Ge),we.pixelStorei(O.UNPACK_SKIP_ROWS,tt),we.pixelStorei(O.UNPACK_SKIP_IMAGES,pt);let sr=E.isDataArrayTexture||E.isData3DTexture,Tr=B.isDataArrayTexture||B.isData3DTexture;if(E.isDepthTexture){let ht=He.get(E),rn=He.get(B),Qn=He.get(ht.__renderTarget),Dt=He.get(rn.__renderTarget);we.bindFramebuffer(O.READ_FRAMEBUFFER,Qn.__webglFramebuffer),we.bindFramebuffer(O.DRAW_FRAMEBUFFER,Dt.__webglFramebuffer);for(let mn=0;mn<Pe;mn++)sr&&(O.framebufferTextureLayer(O.READ_FRAMEBUFFER,O.COLOR_ATTACHMENT0,He.get(E).__webglTexture,$,pt+mn),O.framebufferTextureLayer(O.DRAW_FRAMEBUFFER,O.COLOR_ATTACHMENT0,He.get(B).__webglTexture,Te,Qt+mn)),O.blitFramebuffer(Ge,tt,Ge+Ne,tt+Re,Ve,mt,Ve+Ne,mt+Re,O.DEPTH_BUFFER_BIT,O.NEAREST);we.bindFramebuffer(O.READ_FRAMEBUFFER,null),we.bindFramebuffer(O.DRAW_FRAMEBUFFER,null)}else if($!==0||E.isRenderTargetTexture||He.has(E)){let ht=He.get(E),rn=He.get(B);we.bindFramebuffer(O.READ_FRAMEBUFFER,N),we.bindFramebuffer(O.DRAW_FRAMEBUFFER,F);for(let Qn=0;Qn<Pe;Qn++)sr?O.framebufferTextureLayer(O.READ_FRAMEBUFFER,O.COLOR_ATTACHMENT0,ht.__webglTexture,$,pt+Qn):O.framebufferTexture2D(O.READ_FRAMEBUFFER,O.COLOR_ATTACHMENT0,O.TEXTURE_2D,ht.__webglTexture,$),Tr?O.framebufferTextureLayer(O.DRAW_FRAMEBUFFER,O.COLOR_ATTACHMENT0,rn.__webglTexture,Te,Qt+Qn):O.framebufferTexture2D(O.DRAW_FRAMEBUFFER,O.COLOR_ATTACHMENT0,O.TEXTURE_2D,rn.__webglTexture,Te),$!==0?O.blitFramebuffer(Ge,tt,Ge+Ne,tt+Re,Ve,mt,Ve+Ne,mt+Re,O.COLOR_BUFFER_BIT,O.NEAREST):Tr?O.copyTexSubImage3D(Oe,Te,Ve,mt,Qt+Qn,Ge,tt,Ne,Re):O.copyTexSubImage2D(Oe,Te,Ve,mt,Ge,tt,Ne,Re);we.bindFramebuffer(O.READ_FRAMEBUFFER,null),we.bindFramebuffer(O.DRAW_FRAMEBUFFER,null)}else Tr?E.isDataTexture||E.isData3DTexture?O.texSubImage3D(Oe,Te,Ve,mt,Qt,Ne,Re,Pe,Lt,wn,Pt.data):B.isCompressedArrayTexture?O.compressedTexSubImage3D(Oe,Te,Ve,mt,Qt,Ne,Re,Pe,Lt,Pt.data):O.texSubImage3D(Oe,Te,Ve,mt,Qt,Ne,Re,Pe,Lt,wn,Pt):E.isDataTexture?O.texSubImage2D(O.TEXTURE_2D,Te,Ve,mt,Ne,Re,Lt,wn,Pt.data):E.isCompressedTexture?O.compressedTexSubImage2D(O.TEXTURE_2D,Te,Ve,mt,Pt.width,Pt.height,Lt,Pt.data):O.texSubImage2D(O.TEXTURE_2D,Te,Ve,mt,Ne,Re,Lt,wn,Pt);we.pixelStorei(O.UNPACK_ROW_LENGTH,dn),we.pixelStorei(O.UNPACK_IMAGE_HEIGHT,_t),we.pixelStorei(O.UNPACK_SKIP_PIXELS,Ar),we.pixelStorei(O.UNPACK_SKIP_ROWS,pn),we.pixelStorei(O.UNPACK_SKIP_IMAGES,to),Te===0&&B.generateMipmaps===!0&&B.mipmapsAutoUpdate===!0&&O.generateMipmap(Oe),we.unbindTexture()},this.initRenderTarget=function(E){He.get(E).__webglFramebuffer===void 0&&Ye.setupRenderTarget(E)},this.initTexture=function(E){E.isCubeTexture?Ye.setTextureCube(E,0):E.isData3DTexture?Ye.setTexture3D(E,0):E.isDataArrayTexture||E.isCompressedArrayTexture?Ye.setTexture2DArray(E,0):Ye.setTexture2D(E,0),we.unbindTexture()},this.resetState=function(){Z=0,V=0,le=null,we.reset(),Ee.reset()},typeof __THREE_DEVTOOLS__<"u"&&__THREE_DEVTOOLS__.dispatchEvent(new CustomEvent("observe",{detail:this}))}get coordinateSystem(){return Oi}get outputColorSpace(){return this._outputColorSpace}set outputColorSpace(e){this._outputColorSpace=e;let t=this.getContext();t.drawingBufferColorSpace=vt._getDrawingBufferColorSpace(e),t.unpackColorSpace=vt._getUnpackColorSpace()}};var Km=n=>new Gn(n[1],n[2],n[3],n[0]),tS=n=>(n.normalize(),[n.w,n.x,n.y,n.z]);function o2(n){return new Y(1,0,0).applyQuaternion(Km(n.quaternion))}function nS(n,e){let t=o2(n).multiplyScalar(e);return{positionM:[n.positionM[0]+t.x,n.positionM[1]+t.y,n.positionM[2]+t.z],quaternion:[...n.quaternion]}}function $m(n,e,t){let i=new Gn().setFromAxisAngle(e.clone().normalize(),t);return{positionM:[...n.positionM],quaternion:tS(i.multiply(Km(n.quaternion)))}}function iS(n,e){let t=new Gn().setFromAxisAngle(new Y(1,0,0),e);return{positionM:[...n.positionM],quaternion:tS(Km(n.quaternion).multiply(t))}}var a2=1e-4,qm=.004;function l2(n){return n.altKey?"roll":n.ctrlKey&&n.shiftKey?"tilt":n.ctrlKey?"insert":null}function c2(n,e,t,i,r){switch(e){case"insert":return nS(n,-i*a2);case"roll":return iS(n,t*qm);case"tilt":{let s=new Y(0,1,0).applyQuaternion(r.quaternion),o=new Y(1,0,0).applyQuaternion(r.quaternion);return $m($m(n,s,t*qm),o,i*qm)}}}function rS(n,e,t,i,r){let s=null;n.addEventListener("pointerdown",o=>{let a=l2(o),l=t();!a||!l||(s={start:l,clientX:o.clientX,clientY:o.clientY,mode:a},r(!1),o.preventDefault(),o.stopImmediatePropagation())},{capture:!0}),window.addEventListener("pointermove",o=>{s&&i(c2(s.start,s.mode,o.clientX-s.clientX,o.clientY-s.clientY,e()))}),window.addEventListener("pointerup",()=>{s&&(s=null,r(!0))})}var sS={type:"change"},jm={type:"start"},aS={type:"end"},ff=new ds,oS=new oi,u2=Math.cos(70*Pm.DEG2RAD),Nn=new Y,pi=2*Math.PI,Tt={NONE:-1,ROTATE:0,DOLLY:1,PAN:2,TOUCH_ROTATE:3,TOUCH_PAN:4,TOUCH_DOLLY_PAN:5,TOUCH_DOLLY_ROTATE:6},Jm=1e-6,df=class extends Ll{constructor(e,t=null){super(e,t),this.state=Tt.NONE,this.target=new Y,this.cursor=new Y,this.minDistance=0,this.maxDistance=1/0,this.minZoom=0,this.maxZoom=1/0,this.minTargetRadius=0,this.maxTargetRadius=1/0,this.minPolarAngle=0,this.maxPolarAngle=Math.PI,this.minAzimuthAngle=-1/0,this.maxAzimuthAngle=1/0,this.enableDamping=!1,this.dampingFactor=.05,this.enableZoom=!0,this.zoomSpeed=1,this.enableRotate=!0,this.rotateSpeed=1,this.keyRotateSpeed=1,this.enablePan=!0,this.panSpeed=1,this.screenSpacePanning=!0,this.keyPanSpeed=7,this.zoomToCursor=!1,this.autoRotate=!1,this.autoRotateSpeed=2,this.keys={LEFT:"ArrowLeft",UP:"ArrowUp",RIGHT:"ArrowRight",BOTTOM:"ArrowDown"},this.mouseButtons={LEFT:_s.ROTATE,MIDDLE:_s.DOLLY,RIGHT:_s.PAN},this.touches={ONE:xs.ROTATE,TWO:xs.DOLLY_PAN},this.target0=this.target.clone(),this.position0=this.object.position.clone(),this.zoom0=this.object.zoom,this._cursorStyle="auto",this._domElementKeyEvents=null,this._lastPosition=new Y,this._lastQuaternion=new Gn,this._lastTargetPosition=new Y,this._quat=new Gn().setFromUnitVectors(e.up,new Y(0,1,0)),this._quatInverse=this._quat.clone().invert(),this._spherical=new oa,this._sphericalDelta=new oa,this._scale=1,this._panOffset=new Y,this._rotateStart=new it,this._rotateEnd=new it,this._rotateDelta=new it,this._panStart=new it,this._panEnd=new it,this._panDelta=new it,this._dollyStart=new it,this._dollyEnd=new it,this._dollyDelta=new it,this._dollyDirection=new Y,this._mouse=new it,this._performCursorZoom=!1,this._pointers=[],this._pointerPositions={},this._controlActive=!1,this._onPointerMove=f2.bind(this),this._onPointerDown=h2.bind(this),this._onPointerUp=d2.bind(this),this._onContextMenu=v2.bind(this),this._onMouseWheel=g2.bind(this),this._onKeyDown=y2.bind(this),this._onTouchStart=_2.bind(this),this._onTouchMove=x2.bind(this),this._onMouseDown=p2.bind(this),this._onMouseMove=m2.bind(this),this._interceptControlDown=b2.bind(this),this._interceptControlUp=S2.bind(this),this.domElement!==null&&this.connect(this.domElement),this.update()}set cursorStyle(e){this._cursorStyle=e,e==="grab"?this.domElement.style.cursor="grab":this.domElement.style.cursor="auto"}get cursorStyle(){return this._cursorStyle}connect(e){super.connect(e),this.domElement.addEventListener("pointerdown",this._onPointerDown),this.domElement.addEventListener("pointercancel",this._onPointerUp),this.domElement.addEventListener("contextmenu",this._onContextMenu),this.domElement.addEventListener("wheel",this._onMouseWheel,{passive:!1}),this.domElement.ownerDocument.addEventListener("keydown",this._interceptControlDown,{passive:!0,capture:!0}),this.domElement.style.touchAction="none"}disconnect(){this.state=Tt.NONE,this.domElement.removeEventListener("pointerdown",this._onPointerDown),this.domElement.ownerDocument.removeEventListener("pointermove",this._onPointerMove),this.domElement.ownerDocument.removeEventListener("pointerup",this._onPointerUp),this.domElement.removeEventListener("pointercancel",this._onPointerUp),this.domElement.removeEventListener("wheel",this._onMouseWheel),this.domElement.removeEventListener("contextmenu",this._onContextMenu),this.stopListenToKeyEvents(),this.domElement.ownerDocument.removeEventListener("keydown",this._interceptControlDown,{capture:!0}),this.domElement.ownerDocument.removeEventListener("keyup",this._interceptControlUp,{capture:!0}),this._controlActive=!1,this._pointers.length=0,this._pointerPositions={},this.domElement.style.touchAction="",this.domElement.style.cursor="auto"}dispose(){this.disconnect()}getPolarAngle(){return this._spherical.phi}getAzimuthalAngle(){return this._spherical.theta}getDistance(){return this.object.position.distanceTo(this.target)}listenToKeyEvents(e){e.addEventListener("keydown",this._onKeyDown),this._domElementKeyEvents=e}stopListenToKeyEvents(){this._domElementKeyEvents!==null&&(this._domElementKeyEvents.removeEventListener("keydown",this._onKeyDown),this._domElementKeyEvents=null)}saveState(){this.target0.copy(this.target),this.position0.copy(this.object.position),this.zoom0=this.object.zoom}reset(){this.target.copy(this.target0),this.object.position.copy(this.position0),this.object.zoom=this.zoom0,this.object.updateProjectionMatrix(),this.dispatchEvent(sS),this.update(),this.state=Tt.NONE}pan(e,t){this._pan(e,t),this.update()}dollyIn(e){this._dollyIn(e),this.update()}dollyOut(e){this._dollyOut(e),this.update()}rotateLeft(e){this._rotateLeft(e),this.update()}rotateUp(e){this._rotateUp(e),this.update()}update(e=null){let t=this.object.position;Nn.copy(t).sub(this.target),Nn.applyQuaternion(this._quat),this._spherical.setFromVector3(Nn),this.autoRotate&&this.state===Tt.NONE&&this._rotateLeft(this._getAutoRotationAngle(e)),this.enableDamping?(this._spherical.theta+=this._sphericalDelta.theta*this.dampingFactor,this._spherical.phi+=this._sphericalDelta.phi*this.dampingFactor):(this._spherical.theta+=this._sphericalDelta.theta,this._spherical.phi+=this._sphericalDelta.phi);let i=this.minAzimuthAngle,r=this.maxAzimuthAngle;isFinite(i)&&isFinite(r)&&(i<-Math.PI?i+=pi:i>Math.PI&&(i-=pi),r<-Math.PI?r+=pi:r>Math.PI&&(r-=pi),i<=r?this._spherical.theta=Math.max(i,Math.min(r,this._spherical.theta)):this._spherical.theta=this._spherical.theta>(i+r)/2?Math.max(i,this._spherical.theta):Math.min(r,this._spherical.theta)),this._spherical.phi=Math.max(this.minPolarAngle,Math.min(this.maxPolarAngle,this._spherical.phi)),this._spherical.makeSafe(),this.enableDamping===!0?this.target.addScaledVector(this._panOffset,this.dampingFactor):this.target.add(this._panOffset),this.target.sub(this.cursor),this.target.clampLength(this.minTargetRadius,this.maxTargetRadius),this.target.add(this.cursor);let s=!1;if(this.zoomToCursor&&this._performCursorZoom||this.object.isOrthographicCamera)this._spherical.radius=this._clampDistance(this._spherical.radius);else{let o=this._spherical.radius;this._spherical.radius=this._clampDistance(this._spherical.radius*this._scale),s=o!=this._spherical.radius}if(Nn.setFromSpherical(this._spherical),Nn.applyQuaternion(this._quatInverse),t.copy(this.target).add(Nn),this.object.lookAt(this.target),this.enableDamping===!0?(this._sphericalDelta.theta*=1-this.dampingFactor,this._sphericalDelta.phi*=1-this.dampingFactor,this._panOffset.multiplyScalar(1-this.dampingFactor)):(this._sphericalDelta.set(0,0,0),this._panOffset.set(0,0,0)),this.zoomToCursor&&this._performCursorZoom){let o=null;if(this.object.isPerspectiveCamera){let a=Nn.length();o=this._clampDistance(a*this._scale);let l=a-o;this.object.position.addScaledVector(this._dollyDirection,l),this.object.updateMatrixWorld(),s=!!l}else if(this.object.isOrthographicCamera){let a=new Y(this._mouse.x,this._mouse.y,0);a.unproject(this.object);let l=this.object.zoom;this.object.zoom=Math.max(this.minZoom,Math.min(this.maxZoom,this.object.zoom/this._scale)),this.object.updateProjectionMatrix(),s=l!==this.object.zoom;let c=new Y(this._mouse.x,this._mouse.y,0);c.unproject(this.object),this.object.position.sub(c).add(a),this.object.updateMatrixWorld(),o=Nn.length()}else console.warn("WARNING: OrbitControls.js encountered an unknown camera type - zoom to cursor disabled."),this.zoomToCursor=!1;o!==null&&(this.screenSpacePanning?this.target.set(0,0,-1).transformDirection(this.object.matrix).multiplyScalar(o).add(this.object.position):(ff.origin.copy(this.object.position),ff.direction.set(0,0,-1).transformDirection(this.object.matrix),Math.abs(this.object.up.dot(ff.direction))<u2?this.object.lookAt(this.target):(oS.setFromNormalAndCoplanarPoint(this.object.up,this.target),ff.intersectPlane(oS,this.target))))}else if(this.object.isOrthographicCamera){let o=this.object.zoom;this.object.zoom=Math.max(this.minZoom,Math.min(this.maxZoom,this.object.zoom/this._scale)),o!==this.object.zoom&&(this.object.updateProjectionMatrix(),s=!0)}return this._scale=1,this._performCursorZoom=!1,s||this._lastPosition.distanceToSquared(this.object.position)>Jm||8*(1-this._lastQuaternion.dot(this.object.quaternion))>Jm||this._lastTargetPosition.distanceToSquared(this.target)>Jm?(this.dispatchEvent(sS),this._lastPosition.copy(this.object.position),this._lastQuaternion.copy(this.object.quaternion),this._lastTargetPosition.copy(this.target),!0):!1}_getAutoRotationAngle(e){return e!==null?pi/60*this.autoRotateSpeed*e:pi/60/60*this.autoRotateSpeed}_getZoomScale(e){let t=Math.abs(e*.01);return Math.pow(.95,this.zoomSpeed*t)}_rotateLeft(e){this._sphericalDelta.theta-=e}_rotateUp(e){this._sphericalDelta.phi-=e}_panLeft(e,t){Nn.setFromMatrixColumn(t,0),Nn.multiplyScalar(-e),this._panOffset.add(Nn)}_panUp(e,t){this.screenSpacePanning===!0?Nn.setFromMatrixColumn(t,1):(Nn.setFromMatrixColumn(t,0),Nn.crossVectors(this.object.up,Nn)),Nn.multiplyScalar(e),this._panOffset.add(Nn)}_pan(e,t){let i=this.domElement;if(this.object.isPerspectiveCamera){let r=this.object.position;Nn.copy(r).sub(this.target);let s=Nn.length();s*=Math.tan(this.object.fov/2*Math.PI/180),this._panLeft(2*e*s/i.clientHeight,this.object.matrix),this._panUp(2*t*s/i.clientHeight,this.object.matrix)}else this.object.isOrthographicCamera?(this._panLeft(e*(this.object.right-this.object.left)/this.object.zoom/i.clientWidth,this.object.matrix),this._panUp(t*(this.object.top-this.object.bottom)/this.object.zoom/i.clientHeight,this.object.matrix)):(console.warn("WARNING: OrbitControls.js encountered an unknown camera type - pan disabled."),this.enablePan=!1)}_dollyOut(e){this.object.isPerspectiveCamera||this.object.isOrthographicCamera?this._scale/=e:(console.warn("WARNING: OrbitControls.js encountered an unknown camera type - dolly/zoom disabled."),this.enableZoom=!1)}_dollyIn(e){this.object.isPerspectiveCamera||this.object.isOrthographicCamera?this._scale*=e:(console.warn("WARNING: OrbitControls.js encountered an unknown camera type - dolly/zoom disabled."),this.enableZoom=!1)}_updateZoomParameters(e,t){if(!this.zoomToCursor)return;this._performCursorZoom=!0;let i=this.domElement.getBoundingClientRect(),r=e-i.left,s=t-i.top,o=i.width,a=i.height;this._mouse.x=r/o*2-1,this._mouse.y=-(s/a)*2+1,this._dollyDirection.set(this._mouse.x,this._mouse.y,1).unproject(this.object).sub(this.object.position).normalize()}_clampDistance(e){return Math.max(this.minDistance,Math.min(this.maxDistance,e))}_handleMouseDownRotate(e){this._rotateStart.set(e.clientX,e.clientY)}_handleMouseDownDolly(e){this._updateZoomParameters(e.clientX,e.clientY),this._dollyStart.set(e.clientX,e.clientY)}_handleMouseDownPan(e){this._panStart.set(e.clientX,e.clientY)}_handleMouseMoveRotate(e){this._rotateEnd.set(e.clientX,e.clientY),this._rotateDelta.subVectors(this._rotateEnd,this._rotateStart).multiplyScalar(this.rotateSpeed);let t=this.domElement;this._rotateLeft(pi*this._rotateDelta.x/t.clientHeight),this._rotateUp(pi*this._rotateDelta.y/t.clientHeight),this._rotateStart.copy(this._rotateEnd),this.update()}_handleMouseMoveDolly(e){this._dollyEnd.set(e.clientX,e.clientY),this._dollyDelta.subVectors(this._dollyEnd,this._dollyStart),this._dollyDelta.y>0?this._dollyOut(this._getZoomScale(this._dollyDelta.y)):this._dollyDelta.y<0&&this._dollyIn(this._getZoomScale(this._dollyDelta.y)),this._dollyStart.copy(this._dollyEnd),this.zoomToCursor&&(this._performCursorZoom=!0,this._dollyDirection.set(this._mouse.x,this._mouse.y,1).unproject(this.object).sub(this.object.position).normalize()),this.update()}_handleMouseMovePan(e){this._panEnd.set(e.clientX,e.clientY),this._panDelta.subVectors(this._panEnd,this._panStart).multiplyScalar(this.panSpeed),this._pan(this._panDelta.x,this._panDelta.y),this._panStart.copy(this._panEnd),this.update()}_handleMouseWheel(e){this._updateZoomParameters(e.clientX,e.clientY),e.deltaY<0?this._dollyIn(this._getZoomScale(e.deltaY)):e.deltaY>0&&this._dollyOut(this._getZoomScale(e.deltaY)),this.update()}_handleKeyDown(e){let t=!1;switch(e.code){case this.keys.UP:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateUp(pi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(0,this.keyPanSpeed),t=!0;break;case this.keys.BOTTOM:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateUp(-pi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(0,-this.keyPanSpeed),t=!0;break;case this.keys.LEFT:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateLeft(pi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(this.keyPanSpeed,0),t=!0;break;case this.keys.RIGHT:e.ctrlKey||e.metaKey||e.shiftKey?this.enableRotate&&this._rotateLeft(-pi*this.keyRotateSpeed/this.domElement.clientHeight):this.enablePan&&this._pan(-this.keyPanSpeed,0),t=!0;break}t&&(e.preventDefault(),this.update())}_handleTouchStartRotate(e){if(this._pointers.length===1)this._rotateStart.set(e.pageX,e.pageY);else{let t=this._getSecondPointerPosition(e),i=.5*(e.pageX+t.x),r=.5*(e.pageY+t.y);this._rotateStart.set(i,r)}}_handleTouchStartPan(e){if(this._pointers.length===1)this._panStart.set(e.pageX,e.pageY);else{let t=this._getSecondPointerPosition(e),i=.5*(e.pageX+t.x),r=.5*(e.pageY+t.y);this._panStart.set(i,r)}}_handleTouchStartDolly(e){let t=this._getSecondPointerPosition(e),i=e.pageX-t.x,r=e.pageY-t.y,s=Math.sqrt(i*i+r*r);this._dollyStart.set(0,s)}_handleTouchStartDollyPan(e){this.enableZoom&&this._handleTouchStartDolly(e),this.enablePan&&this._handleTouchStartPan(e)}_handleTouchStartDollyRotate(e){this.enableZoom&&this._handleTouchStartDolly(e),this.enableRotate&&this._handleTouchStartRotate(e)}_handleTouchMoveRotate(e){if(this._pointers.length==1)this._rotateEnd.set(e.pageX,e.pageY);else{let i=this._getSecondPointerPosition(e),r=.5*(e.pageX+i.x),s=.5*(e.pageY+i.y);this._rotateEnd.set(r,s)}this._rotateDelta.subVectors(this._rotateEnd,this._rotateStart).multiplyScalar(this.rotateSpeed);let t=this.domElement;this._rotateLeft(pi*this._rotateDelta.x/t.clientHeight),this._rotateUp(pi*this._rotateDelta.y/t.clientHeight),this._rotateStart.copy(this._rotateEnd)}_handleTouchMovePan(e){if(this._pointers.length===1)this._panEnd.set(e.pageX,e.pageY);else{let t=this._getSecondPointerPosition(e),i=.5*(e.pageX+t.x),r=.5*(e.pageY+t.y);this._panEnd.set(i,r)}this._panDelta.subVectors(this._panEnd,this._panStart).multiplyScalar(this.panSpeed),this._pan(this._panDelta.x,this._panDelta.y),this._panStart.copy(this._panEnd)}_handleTouchMoveDolly(e){let t=this._getSecondPointerPosition(e),i=e.pageX-t.x,r=e.pageY-t.y,s=Math.sqrt(i*i+r*r);this._dollyEnd.set(0,s),this._dollyDelta.set(0,Math.pow(this._dollyEnd.y/this._dollyStart.y,this.zoomSpeed)),this._dollyOut(this._dollyDelta.y),this._dollyStart.copy(this._dollyEnd);let o=(e.pageX+t.x)*.5,a=(e.pageY+t.y)*.5;this._updateZoomParameters(o,a)}_handleTouchMoveDollyPan(e){this.enableZoom&&this._handleTouchMoveDolly(e),this.enablePan&&this._handleTouchMovePan(e)}_handleTouchMoveDollyRotate(e){this.enableZoom&&this._handleTouchMoveDolly(e),this.enableRotate&&this._handleTouchMoveRotate(e)}_addPointer(e){this._pointers.push(e.pointerId)}_removePointer(e){delete this._pointerPositions[e.pointerId];for(let t=0;t<this._pointers.length;t++)if(this._pointers[t]==e.pointerId){this._pointers.splice(t,1);return}}_isTrackingPointer(e){for(let t=0;t<this._pointers.length;t++)if(this._pointers[t]==e.pointerId)return!0;return!1}_trackPointer(e){let t=this._pointerPositions[e.pointerId];t===void 0&&(t=new it,this._pointerPositions[e.pointerId]=t),t.set(e.pageX,e.pageY)}_getSecondPointerPosition(e){let t=e.pointerId===this._pointers[0]?this._pointers[1]:this._pointers[0];return this._pointerPositions[t]}_customWheelEvent(e){let t=e.deltaMode,i={clientX:e.clientX,clientY:e.clientY,deltaY:e.deltaY};switch(t){case 1:i.deltaY*=16;break;case 2:i.deltaY*=100;break}return e.ctrlKey&&!this._controlActive&&(i.deltaY*=10),i}};function h2(n){this.enabled!==!1&&(this._pointers.length===0&&(this.domElement.setPointerCapture(n.pointerId),this.domElement.ownerDocument.addEventListener("pointermove",this._onPointerMove),this.domElement.ownerDocument.addEventListener("pointerup",this._onPointerUp)),!this._isTrackingPointer(n)&&(this._addPointer(n),n.pointerType==="touch"?this._onTouchStart(n):this._onMouseDown(n),this._cursorStyle==="grab"&&(this.domElement.style.cursor="grabbing")))}function f2(n){this.enabled!==!1&&(n.pointerType==="touch"?this._onTouchMove(n):this._onMouseMove(n))}function d2(n){switch(this._removePointer(n),this._pointers.length){case 0:this.domElement.releasePointerCapture(n.pointerId),this.domElement.ownerDocument.removeEventListener("pointermove",this._onPointerMove),this.domElement.ownerDocument.removeEventListener("pointerup",this._onPointerUp),this.dispatchEvent(aS),this.state=Tt.NONE,this._cursorStyle==="grab"&&(this.domElement.style.cursor="grab");break;case 1:let e=this._pointers[0],t=this._pointerPositions[e];this._onTouchStart({pointerId:e,pageX:t.x,pageY:t.y});break}}function p2(n){let e;switch(n.button){case 0:e=this.mouseButtons.LEFT;break;case 1:e=this.mouseButtons.MIDDLE;break;case 2:e=this.mouseButtons.RIGHT;break;default:e=-1}switch(e){case _s.DOLLY:if(this.enableZoom===!1)return;this._handleMouseDownDolly(n),this.state=Tt.DOLLY;break;case _s.ROTATE:if(n.ctrlKey||n.metaKey||n.shiftKey){if(this.enablePan===!1)return;this._handleMouseDownPan(n),this.state=Tt.PAN}else{if(this.enableRotate===!1)return;this._handleMouseDownRotate(n),this.state=Tt.ROTATE}break;case _s.PAN:if(n.ctrlKey||n.metaKey||n.shiftKey){if(this.enableRotate===!1)return;this._handleMouseDownRotate(n),this.state=Tt.ROTATE}else{if(this.enablePan===!1)return;this._handleMouseDownPan(n),this.state=Tt.PAN}break;default:this.state=Tt.NONE}this.state!==Tt.NONE&&this.dispatchEvent(jm)}function m2(n){switch(this.state){case Tt.ROTATE:if(this.enableRotate===!1)return;this._handleMouseMoveRotate(n);break;case Tt.DOLLY:if(this.enableZoom===!1)return;this._handleMouseMoveDolly(n);break;case Tt.PAN:if(this.enablePan===!1)return;this._handleMouseMovePan(n);break}}function g2(n){this.enabled===!1||this.enableZoom===!1||this.state!==Tt.NONE||(n.preventDefault(),this.dispatchEvent(jm),this._handleMouseWheel(this._customWheelEvent(n)),this.dispatchEvent(aS))}function y2(n){this.enabled!==!1&&this._handleKeyDown(n)}function _2(n){switch(this._trackPointer(n),this._pointers.length){case 1:switch(this.touches.ONE){case xs.ROTATE:if(this.enableRotate===!1){this.state=Tt.NONE;break}this._handleTouchStartRotate(n),this.state=Tt.TOUCH_ROTATE;break;case xs.PAN:if(this.enablePan===!1){this.state=Tt.NONE;break}this._handleTouchStartPan(n),this.state=Tt.TOUCH_PAN;break;default:this.state=Tt.NONE}break;case 2:switch(this.touches.TWO){case xs.DOLLY_PAN:if(this.enableZoom===!1&&this.enablePan===!1)return;this._handleTouchStartDollyPan(n),this.state=Tt.TOUCH_DOLLY_PAN;break;case xs.DOLLY_ROTATE:if(this.enableZoom===!1&&this.enableRotate===!1)return;this._handleTouchStartDollyRotate(n),this.state=Tt.TOUCH_DOLLY_ROTATE;break;default:this.state=Tt.NONE}break;default:this.state=Tt.NONE}this.state!==Tt.NONE&&this.dispatchEvent(jm)}function x2(n){switch(this._trackPointer(n),this.state){case Tt.TOUCH_ROTATE:if(this.enableRotate===!1)return;this._handleTouchMoveRotate(n),this.update();break;case Tt.TOUCH_PAN:if(this.enablePan===!1)return;this._handleTouchMovePan(n),this.update();break;case Tt.TOUCH_DOLLY_PAN:if(this.enableZoom===!1&&this.enablePan===!1)return;this._handleTouchMoveDollyPan(n),this.update();break;case Tt.TOUCH_DOLLY_ROTATE:if(this.enableZoom===!1&&this.enableRotate===!1)return;this._handleTouchMoveDollyRotate(n),this.update();break;default:this.state=Tt.NONE}}function v2(n){this.enabled!==!1&&n.preventDefault()}function b2(n){n.key==="Control"&&(this._controlActive=!0,this.domElement.ownerDocument.addEventListener("keyup",this._interceptControlUp,{passive:!0,capture:!0}))}function S2(n){n.key==="Control"&&(this._controlActive=!1,this.domElement.ownerDocument.removeEventListener("keyup",this._interceptControlUp,{passive:!0,capture:!0}))}var M2={stuck:2188972,slipping:15830785,tip:15149450,other:10066329};function E2(n,e){let t=Math.min(Math.max(n,0),1);t<.5?e.setRGB(1,1,1-2*t*.9):e.setRGB(1,1-(t-.5)*1.6,.1)}var pf=class{constructor(e){this.canvas=e;this.renderer=new cf({canvas:e,antialias:!0,preserveDrawingBuffer:!0}),this.renderer.setPixelRatio(1),this.renderer.localClippingEnabled=!0,this.renderer.setClearColor(16777215),this.camera=new ai(40,e.width/e.height,1e-4,10),this.controls=new df(this.camera,e),this.controls.enableDamping=!1,this.scene.add(new Pl(16777215,.55));let t=new ra(16777215,.9);t.position.set(1,2,3),this.scene.add(t);let i=new ra(16777215,.4);this.camera.add(i),this.scene.add(this.camera),this.needle=new bl(new ci,new ea({color:2236962,linewidth:2})),this.needle.frustumCulled=!1,this.points=new Sl(new ci,new ta({size:7,sizeAttenuation:!1,vertexColors:!0,depthTest:!1})),this.points.frustumCulled=!1,this.points.renderOrder=2,this.scene.add(this.needle,this.points)}canvas;renderer;scene=new _l;camera;controls;section=new oi(new Y(0,1,0),0);sectionOn=!1;tissue=null;surface=null;centre=new Y;sizeM=.1;displacementScaleM=.001;needle;points;targetMeshes=[];unitSphere=new Tl(1,24,16);colour=new ft;setSurface(e){this.tissue&&(this.scene.remove(this.tissue),this.tissue.geometry.dispose()),this.surface=e;let t=new ci;t.setAttribute("position",new $n(new Float32Array(e.positionsM),3)),t.setAttribute("color",new $n(new Float32Array(e.positionsM.length).fill(1),3)),t.setIndex(new $n(e.triangles,1)),t.computeVertexNormals(),t.computeBoundingBox();let i=new ia({vertexColors:!0,side:Fi,transparent:!0,opacity:.85,clippingPlanes:[]});this.tissue=new Ti(t,i),this.scene.add(this.tissue);let r=t.boundingBox??new _r;r.getCenter(this.centre),this.sizeM=r.getSize(new Y).length()||.1,this.camera.near=this.sizeM*.001,this.camera.far=this.sizeM*50,this.camera.position.copy(this.centre).add(new Y(.9,-1.4,.8).multiplyScalar(this.sizeM)),this.camera.up.set(0,0,1),this.camera.updateProjectionMatrix(),this.controls.target.copy(this.centre),this.controls.update(),this.setSection(this.sectionOn,.5)}setSection(e,t){this.sectionOn=e;let i=this.tissue?.geometry.boundingBox;i&&(this.section.constant=-(i.min.y+t*(i.max.y-i.min.y))),this.tissue&&(this.tissue.material.clippingPlanes=e?[this.section]:[])}show(e){let t=this.surface;if(t&&this.tissue&&e.displacementM&&e.displacementM.length===t.positionsM.length){let o=this.tissue.geometry.getAttribute("position"),a=this.tissue.geometry.getAttribute("color"),l=0,c=e.displacementM;for(let u=0;u<c.length;u+=3){let h=Math.hypot(c[u],c[u+1],c[u+2]);h>l&&(l=h)}this.displacementScaleM=l>0?l:1;for(let u=0,h=0;u<c.length;u+=3,h++)o.setXYZ(h,t.positionsM[u]+c[u],t.positionsM[u+1]+c[u+1],t.positionsM[u+2]+c[u+2]),E2(Math.sqrt(Math.hypot(c[u],c[u+1],c[u+2])/this.displacementScaleM),this.colour),a.setXYZ(h,this.colour.r,this.colour.g,this.colour.b);o.needsUpdate=!0,a.needsUpdate=!0,this.tissue.geometry.computeVertexNormals()}this.needle.geometry.setFromPoints(e.needleM.map(([o,a,l])=>new Y(o,a,l)));let i=this.points.geometry,r=new Float32Array(e.points.length*3),s=new Float32Array(e.points.length*3);for(e.points.forEach((o,a)=>{r.set(o.posM,3*a),this.colour.setHex(M2[o.state]),s.set([this.colour.r,this.colour.g,this.colour.b],3*a)}),i.setAttribute("position",new $n(r,3)),i.setAttribute("color",new $n(s,3));this.targetMeshes.length<e.targets.length;){let o=new Ti(this.unitSphere,new ia({transparent:!0,opacity:.75}));this.targetMeshes.push(o),this.scene.add(o)}this.targetMeshes.forEach((o,a)=>{let l=e.targets[a];o.visible=l!==void 0,l&&(o.position.set(...l.centreM),o.scale.setScalar(l.radiusM),o.material.color.setHex(l.hit?1810039:7696563))})}render(){this.renderer.render(this.scene,this.camera)}};var w2=20,A2=500,T2=220,gf=et("view",HTMLCanvasElement),mf=et("view3",HTMLCanvasElement),Js=null,lS=null,R2=0;function I2(){let n=me.dim===3;if(gf.hidden=n,mf.hidden=!n,et("controls3").hidden=!n,!n||!me.surface3)return;if(!Js){Js=new pf(mf);let t=Js;rS(mf,()=>t.camera,()=>me.driving.commanded3??(me.frame?.d3?$x(me.frame.d3):null),i=>{me.mode==="live"&&Wy(i)},i=>{t.controls.enabled=i}),t.controls.addEventListener("change",()=>{me.dirty=!0})}lS!==me.surface3&&(lS=me.surface3,Js.setSurface(me.surface3)),Js.setSection(et("section-on",HTMLInputElement).checked,Number(et("section-at",HTMLInputElement).value));let e=me.frame?Kx(me.frame):null;e&&Js.show(e),Js.render(),an("view3Draws",++R2)}var cS=new Jc(et("plot-time"),et("plot-depth"),A2,T2);function uS(){if(me.dirty){me.dirty=!1,me.dim===3?I2():(mf.hidden=!0,et("controls3").hidden=!0,gf.hidden=!1,zy(gf,me));let n=me.playback;me.mode==="playback"&&n.history?cS.show(n.history,null,me.frame?vo(me.frame):null):cS.show(me.history,w2,null)}requestAnimationFrame(uS)}Xy(gf);et("refresh-sessions").addEventListener("click",()=>{fu()});et("session-select").addEventListener("change",sv);et("connect").addEventListener("click",rv);et("create").addEventListener("click",()=>{iv()});et("flip-bevel").addEventListener("click",()=>{Yy()});et("rec-refresh").addEventListener("click",()=>{uu()});et("rec-start").addEventListener("click",()=>{wp(!0)});et("rec-stop").addEventListener("click",()=>{wp(!1)});et("rec-load").addEventListener("click",()=>{jx()});et("live").addEventListener("click",()=>{tv(),me.session&&il(me.session.id,me.session.token)});et("slider").addEventListener("input",Qx);for(let n of["section-on","section-at"])et(n).addEventListener("input",()=>{me.dirty=!0});et("play").addEventListener("click",ev);async function C2(){requestAnimationFrame(uS);let n=new URLSearchParams(window.location.search),e=n.get("session"),t=n.get("token");e&&t&&hr.set(e,t),await fu(e??void 0),uu(),an("ready","1"),e&&t&&(et("token",HTMLInputElement).value=t,await il(e,t))}C2();
